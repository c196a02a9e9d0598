// The paper's Fig. 8 drawn with gnuplot, shared by `graspsynth analyze --plot` and
// `graspsynth run`.

#include "apps/figure8.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>
#include <optional>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/input_file.hpp"
#include "scene/triangle_mesh.hpp"

extern char** environ;

namespace graspsynth::apps {
namespace {

namespace fs = std::filesystem;

// A folder under the system's temporary folder, removed with everything in it on destruction.
class TempFolder {
 public:
  TempFolder() {
    std::string pattern = (fs::temp_directory_path() / "graspsynth-plot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw InputError("cannot create a temporary folder '" + pattern +
                       "': " + std::strerror(errno));
    }
    path_ = pattern;
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw InputError("cannot write '" + path.string() + "'");
}

// The file's text, or nothing when there is none (gnuplot wrote no log or no figure).
std::string ReadText(const fs::path& path) {
  try {
    return ReadInputFile(path, input_kind::kToolOutput);
  } catch (const InputError&) {
    return "";  // gnuplot wrote nothing there
  }
}

// Runs `program script` with stdout and stderr sent to `log`; throws with a clear message when
// the program cannot be started or fails.
void RunGnuplot(const std::string& program, const fs::path& script, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string arg0 = program;
  std::string arg1 = script.string();
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int error = ::posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    throw InputError("--plot needs gnuplot, but '" + program + "' could not be started (" +
                     std::strerror(error) +
                     "); install it (Debian: apt-get install gnuplot-nox) or name the program "
                     "with --gnuplot");
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR)
      throw InputError(std::string("waiting for gnuplot: ") + std::strerror(errno));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw InputError("gnuplot ('" + program + "') failed on '" + script.string() + "':\n" +
                     ReadText(log));
  }
}

// The paper's symbols of Table I (*, o, x, +, *, square, diamond, triangle down, triangle up) as
// gnuplot point types, with the second * made a filled circle so that all nine differ; more
// orientations reuse them cyclically.
int PointType(size_t index) {
  constexpr int kTypes[] = {3, 6, 2, 1, 7, 4, 12, 10, 8, 5, 9, 11, 13, 14, 15};
  return kTypes[index % (sizeof(kTypes) / sizeof(kTypes[0]))];
}

// The corners of a part's footprint on the table plane, in O: a box's rectangle, the
// bounding rectangle of a mesh, and none for round parts (circles, drawn once).
std::vector<Eigen::Vector2d> Footprint(const CollisionShape& s) {
  Eigen::Vector2d half, mid = s.X_LG.translation().head<2>();
  if (s.kind == CollisionShape::Kind::kBox) {
    half = 0.5 * s.size.head<2>();
  } else if (s.kind == CollisionShape::Kind::kMesh) {
    const Eigen::Vector3d lo = s.mesh->BoxMin(), hi = s.mesh->BoxMax();
    half = 0.5 * (hi - lo).head<2>();
    mid += s.X_LG.linear().topLeftCorner<2, 2>() * (0.5 * (lo + hi)).head<2>();
  } else {
    return {};
  }
  const Eigen::Vector2d ax = s.X_LG.linear().col(0).head<2>();
  const Eigen::Vector2d ay = s.X_LG.linear().col(1).head<2>();
  return {mid - half.x() * ax + half.y() * ay, mid + half.x() * ax + half.y() * ay,
          mid + half.x() * ax - half.y() * ay, mid - half.x() * ax - half.y() * ay,
          mid - half.x() * ax + half.y() * ay};
}

// The object's outline (object.dat), seen from above: its round parts (cylinders, spheres,
// capsules) as circles, once, and its other parts' footprints at the first, middle and last
// orientation of `rows`; `labels` gets the gnuplot labels of those orientations. Parts that
// touch only the table (supports) are left out.
std::string ObjectData(const SceneModel& scene, const std::vector<OrientationStats>& rows,
                       std::string* labels) {
  const ObjectModel& o = scene.object;
  std::string object;
  double reach = 0.0;  // farthest footprint corner along the object's x axis
  for (const ObjectPart& part : o.parts) {
    if (!part.touches_robot()) continue;
    const CollisionShape& s = part.shape;
    for (const Eigen::Vector2d& c : Footprint(s)) reach = std::max(reach, c.x());
    if (s.kind == CollisionShape::Kind::kBox || s.kind == CollisionShape::Kind::kMesh) continue;
    const Eigen::Vector2d centre = s.X_LG.translation().head<2>();
    reach = std::max(reach, centre.x() + s.size[0]);
    if (!object.empty()) object += "\n";
    for (int i = 0; i <= 72; ++i) {
      const double a = 2.0 * M_PI * i / 72.0;
      object += StreamNumber(centre.x() + s.size[0] * std::cos(a), 9) + " " +
                StreamNumber(centre.y() + s.size[0] * std::sin(a), 9) + "\n";
    }
  }
  std::vector<double> thetas;
  if (rows.empty()) {
    thetas = {20.0, 60.0, 100.0};
  } else {
    thetas = {rows.front().theta_deg};
    if (rows.size() > 2) thetas.push_back(rows[rows.size() / 2].theta_deg);
    if (rows.size() > 1) thetas.push_back(rows.back().theta_deg);
  }
  const std::string what = o.handle ? "handle" : o.name;
  for (double theta_deg : thetas) {
    const double phi = theta_deg * kDeg + scene.object_yaw_offset;
    const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
    const Eigen::Vector2d v(-u.y(), u.x());
    for (const ObjectPart& part : o.parts) {
      if (!part.touches_robot()) continue;
      const std::vector<Eigen::Vector2d> corners = Footprint(part.shape);
      if (corners.empty()) continue;
      object += "\n";
      for (const Eigen::Vector2d& c : corners) {
        const Eigen::Vector2d w = c.x() * u + c.y() * v;
        object += StreamNumber(w.x(), 9) + " " + StreamNumber(w.y(), 9) + "\n";
      }
    }
    const Eigen::Vector2d tip = (reach + 0.12) * u;
    *labels += "set label '" + what + " θ = " + StreamNumber(theta_deg, 9) + "' at " +
               StreamNumber(tip.x(), 9) + "," + StreamNumber(tip.y(), 9) +
               " font ',9' textcolor rgb '#606060' center\n";
  }
  return object;
}

// The wrist line over the span of the fitted points, 5 cm beyond each end (line.dat); "" when
// the line is not usable.
std::string WristLineData(const DemonstrationAnalysis& analysis) {
  std::string line_data;
  const WristLineResult& line = analysis.line;
  if (!line.usable()) return line_data;
  double lo = 0.0, hi = 0.0;
  for (size_t i = 0; i < analysis.fit_points.size(); ++i) {
    const double s = line.line.direction.dot(analysis.fit_points[i] - line.line.point);
    lo = i == 0 ? s : std::min(lo, s);
    hi = i == 0 ? s : std::max(hi, s);
  }
  for (double s : {lo - 0.05, hi + 0.05}) {
    const Eigen::Vector2d p = line.line.point + s * line.line.direction;
    line_data += StreamNumber(p.x(), 9) + " " + StreamNumber(p.y(), 9) + "\n";
  }
  return line_data;
}

// The gnuplot script drawing figure.svg from the data files in `dir`: the grasp region of
// radius `r`, the object with its `labels`, the wrist line when `with_line`, the means of `rows`.
std::string Figure8Script(const fs::path& dir, const std::string& labels, double r, bool with_line,
                          const std::vector<OrientationStats>& rows) {
  // the data files are named relative to the folder, which the script changes to first.
  std::string script = "cd '" + dir.string() + "'\n";
  script += "set encoding utf8\n";
  script += "set terminal svg size 900,800 enhanced font 'Helvetica,12' background rgb 'white'\n";
  script += "set output 'figure.svg'\n";
  script +=
      "set title 'Average pre-grasp and grasp wrist positions per object orientation "
      "(top view, object-centred)'\n";
  script += "set xlabel 'x (m)'\nset ylabel 'y (m)'\n";
  script += "set size ratio -1\nset grid lc rgb '#dddddd'\n";
  script += "set key outside right top box\n";
  script += labels;
  script +=
      "plot 'region.dat'"
      " using 1:2 with lines dt 2 lc rgb '#9090c0' title 'grasp region (" +
      StreamNumber(r, 9) + " m)', \\\n";
  script += "     'object.dat' using 1:2 with lines lw 2 lc rgb '#606060' title 'object', \\\n";
  if (with_line) {
    script +=
        "     'line.dat' using 1:2 with lines lw 2 lc rgb '#2ca02c' title 'wrist line (fit)', "
        "\\\n";
  }
  script += "     keyentry with points pt 7 lc rgb '#1f77b4' title 'pre-grasp (mean)', \\\n";
  script += "     keyentry with points pt 7 lc rgb '#d62728' title 'grasp (mean)'";
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string pt = std::to_string(PointType(i));
    const std::string block = "'means.dat' index " + std::to_string(i);
    script += ", \\\n     " + block + " using 1:2 with points pt " + pt +
              " ps 1.4 lc rgb '#1f77b4' notitle";
    script += ", \\\n     " + block + " using 3:4 with points pt " + pt +
              " ps 1.4 lc rgb '#d62728' title 'θ = " + StreamNumber(rows[i].theta_deg, 9) + "'";
  }
  script += "\nunset output\n";
  return script;
}

}  // namespace

// The paper's Fig. 8 in the object-centred frame: mean pre-grasp and grasp positions per
// orientation, the wrist line, the grasp region, the object outline at a few orientations.
void DrawFigure8(const DemonstrationAnalysis& analysis, const SceneModel& scene,
                 const std::string& gnuplot, const fs::path& svg_path) {
  const TempFolder temp;
  const fs::path dir = temp.path();
  if (dir.string().find('\'') != std::string::npos) {
    throw InputError("--plot: the temporary folder '" + dir.string() +
                     "' has a quote in its name, which gnuplot cannot take; set TMPDIR");
  }
  const std::vector<OrientationStats>& rows = analysis.table.orientations;

  std::string labels;
  WriteText(dir / "object.dat", ObjectData(scene, rows, &labels));

  // the grasp region boundary (its horizontal section).
  std::string region;
  const double r = analysis.options.segmentation.region.radius;
  for (int i = 0; i <= 180; ++i) {
    const double a = 2.0 * M_PI * i / 180.0;
    region += StreamNumber(r * std::cos(a), 9) + " " + StreamNumber(r * std::sin(a), 9) + "\n";
  }
  WriteText(dir / "region.dat", region);

  // one block per orientation: pre-grasp mean, then grasp mean.
  std::string means;
  for (const OrientationStats& row : rows) {
    means += StreamNumber(row.pregrasp.mean_xy.x(), 9) + " " +
             StreamNumber(row.pregrasp.mean_xy.y(), 9) + " " +
             StreamNumber(row.grasp.mean_xy.x(), 9) + " " + StreamNumber(row.grasp.mean_xy.y(), 9) +
             "\n\n\n";
  }
  WriteText(dir / "means.dat", means.empty() ? std::string("\n") : means);

  const std::string line_data = WristLineData(analysis);
  if (!line_data.empty()) WriteText(dir / "line.dat", line_data);

  const fs::path svg = dir / "figure.svg";
  const fs::path script_path = dir / "figure8.gp";
  WriteText(script_path, Figure8Script(dir, labels, r, !line_data.empty(), rows));

  RunGnuplot(gnuplot, script_path, dir / "gnuplot.log");
  const std::string contents = ReadText(svg);
  if (contents.empty()) {
    throw InputError("gnuplot ('" + gnuplot + "') wrote no SVG:\n" + ReadText(dir / "gnuplot.log"));
  }
  WriteFileAtomically(svg_path, contents);
}

}  // namespace graspsynth::apps
