#include "study/study_codec.hpp"

#include "common/byte_codec.hpp"

namespace graspsynth {
namespace {

void WriteHold(ByteWriter& w, const HoldQuality& h) {
  w.Double(h.end_tilt);
  w.Double(h.max_tilt);
  w.Double(h.slip);
  w.Double(h.slip_angle);
  w.Int(h.contacts);
  for (double s : h.load_share) w.Double(s);
}

HoldQuality ReadHold(ByteReader& r) {
  HoldQuality h;
  h.end_tilt = r.Double();
  h.max_tilt = r.Double();
  h.slip = r.Double();
  h.slip_angle = r.Double();
  h.contacts = r.Int32();
  for (double& s : h.load_share) s = r.Double();
  return h;
}

void WriteCell(ByteWriter& w, const SensitivityCell& c) {
  const PhysicsVariation& v = c.physics.variation;
  for (double x :
       {v.object_hand_friction, v.object_table_friction, v.contact_stiffness, v.contact_damping,
        v.object_mass, v.object_com_offset.x(), v.object_com_offset.y(), v.object_com_offset.z(),
        v.hand_effort, c.physics.time_step}) {
    w.Double(x);
  }
  w.Int(c.trials);
  w.Int(c.successes);
  w.String(c.failures);
}

SensitivityCell ReadCell(ByteReader& r) {
  SensitivityCell c;
  PhysicsVariation& v = c.physics.variation;
  for (double* x :
       {&v.object_hand_friction, &v.object_table_friction, &v.contact_stiffness, &v.contact_damping,
        &v.object_mass, &v.object_com_offset.x(), &v.object_com_offset.y(),
        &v.object_com_offset.z(), &v.hand_effort, &c.physics.time_step}) {
    *x = r.Double();
  }
  c.trials = r.Int32();
  c.successes = r.Int32();
  c.failures = r.String();
  return c;
}

void WriteSensitivity(ByteWriter& w, const SensitivityResult& s) {
  w.Int(s.trials_per_cell);
  w.UInt(s.rows.size());
  for (const SensitivityRow& row : s.rows) {
    w.EnumValue(row.factor);
    WriteCell(w, row.low);
    WriteCell(w, row.high);
  }
  w.Double(s.wall_time);
}

SensitivityResult ReadSensitivity(ByteReader& r) {
  SensitivityResult s;
  s.trials_per_cell = r.Int32();
  const int64_t rows = r.IntIn(0, 1000);
  for (int64_t k = 0; k < rows; ++k) {
    SensitivityRow row;
    row.factor = r.EnumValue(PhysicsFactor::kStep);
    row.low = ReadCell(r);
    row.high = ReadCell(r);
    s.rows.push_back(row);
  }
  s.wall_time = r.Double();
  return s;
}

void WriteFallback(ByteWriter& w, const FallbackReason& f) {
  w.EnumValue(f.kind);
  w.String(f.bracket_reason);
  w.Double(f.lower_deg);
  w.Double(f.upper_deg);
  w.Double(f.used_deg);
  w.Bool(f.robust);
  w.Double(f.min_psi_width);
  w.Bool(f.line_unreachable);
  w.Int(f.side);
  w.Bool(f.blend_failed);
  w.String(f.cell);
  w.String(f.used_placement);
}

FallbackReason ReadFallback(ByteReader& r) {
  FallbackReason f;
  f.kind = r.EnumValue(FallbackKind::kPartialBlend);
  f.bracket_reason = r.String();
  f.lower_deg = r.Double();
  f.upper_deg = r.Double();
  f.used_deg = r.Double();
  f.robust = r.Bool();
  f.min_psi_width = r.Double();
  f.line_unreachable = r.Bool();
  f.side = r.Int32();
  f.blend_failed = r.Bool();
  f.cell = r.String();
  f.used_placement = r.String();
  return f;
}

}  // namespace

std::string EncodeStudyRow(const StudyRow& row) {
  ByteWriter w;
  w.Double(row.theta_deg);
  WriteOptional(w, row.at, [&](const Eigen::Vector2d& at) {
    w.Double(at.x());
    w.Double(at.y());
  });
  w.String(row.method);
  w.String(row.message);
  WriteOptional(w, row.used, [&](SynthesisMethod m) { w.EnumValue(m); });
  w.Bool(row.fallback);
  WriteFallback(w, row.fallback_reason);
  w.Bool(row.refined);
  w.Bool(row.gate_run);
  WriteOptional(w, row.status, [&](SynthesisStatus s) { w.EnumValue(s); });
  w.Bool(row.nominal_success);
  WriteOptional(w, row.nominal_outcome, [&](TrialOutcome o) { w.EnumValue(o); });
  w.String(row.nominal_reason);
  w.Int(row.trials);
  w.Int(row.successes);
  w.Double(row.robustness);
  w.Double(row.ci_low);
  w.Double(row.ci_high);
  w.Bool(row.passed);
  w.String(row.gate_reason);
  w.Double(row.epsilon);
  w.Bool(row.force_closure);
  w.String(row.failures);
  WriteHold(w, row.nominal_hold);
  WriteOptional(w, row.sensitivity, [&](const SensitivityResult& s) { WriteSensitivity(w, s); });
  w.UInt(row.seed);
  w.Double(row.synthesis_s);
  w.Double(row.gate_s);
  w.Doubles(row.source_thetas_deg);
  return w.Take();
}

StudyRow DecodeStudyRow(std::string_view bytes, const std::string& source) {
  ByteReader r(bytes, source);
  StudyRow row;
  row.theta_deg = r.Double();
  row.at = ReadOptional(r, [&] {
    const double x = r.Double();
    return Eigen::Vector2d(x, r.Double());
  });
  row.method = r.String();
  row.message = r.String();
  row.used = ReadOptional(r, [&] { return r.EnumValue(SynthesisMethod::kNearest); });
  row.fallback = r.Bool();
  row.fallback_reason = ReadFallback(r);
  row.refined = r.Bool();
  row.gate_run = r.Bool();
  row.status = ReadOptional(r, [&] { return r.EnumValue(SynthesisStatus::kUnreachable); });
  row.nominal_success = r.Bool();
  row.nominal_outcome = ReadOptional(r, [&] { return r.EnumValue(TrialOutcome::kUnstable); });
  row.nominal_reason = r.String();
  row.trials = r.Int32();
  row.successes = r.Int32();
  row.robustness = r.Double();
  row.ci_low = r.Double();
  row.ci_high = r.Double();
  row.passed = r.Bool();
  row.gate_reason = r.String();
  row.epsilon = r.Double();
  row.force_closure = r.Bool();
  row.failures = r.String();
  row.nominal_hold = ReadHold(r);
  row.sensitivity = ReadOptional(r, [&] { return ReadSensitivity(r); });
  row.seed = r.UInt();
  row.synthesis_s = r.Double();
  row.gate_s = r.Double();
  row.source_thetas_deg = r.Doubles();
  r.Finish();
  return row;
}

}  // namespace graspsynth
