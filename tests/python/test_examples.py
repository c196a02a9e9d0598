"""examples/python runs and draws its figure."""

import os
import subprocess
import sys


def test_the_synthesis_example_writes_its_figure(repo, tmp_path):
    out = tmp_path / "grasps.png"
    done = subprocess.run(
        [sys.executable, str(repo / "examples" / "python" / "synthesize_and_plot.py"),
         "--orientations", "35,65", "--perturb", "2", "--out", str(out)],
        capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"), check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "2 of 2 synthesized grasps lifted the pan" in done.stdout
    assert "trial success" in done.stdout  # the outcome's label, as the files write it
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
