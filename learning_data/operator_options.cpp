#include "learning_data/operator_options.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/json_reader.hpp"
#include "learning_data/demo_directory.hpp"

namespace graspsynth {
namespace {

constexpr int64_t kMaxCount = std::numeric_limits<int>::max();
using json = nlohmann::ordered_json;

json HandToDeg(const HandVector& f) {
  json a = json::array();
  for (int i = 0; i < kHandDof; ++i) a.push_back(f[i] / kDeg);
  return a;
}

// A scalar field of an options struct T: name, member, and whether the file holds degrees.
template <class T>
struct ScalarField {
  const char* name;
  double T::*member;
  bool degrees;
};
constexpr ScalarField<OperatorOptions> kScalars[] = {
    {"sample_rate_hz", &OperatorOptions::sample_rate_hz, false},
    {"rest_distance", &OperatorOptions::rest_distance, false},
    {"rest_turn_deg", &OperatorOptions::rest_turn, true},
    {"rest_height", &OperatorOptions::rest_height, false},
    {"entry_out", &OperatorOptions::entry_out, false},
    {"entry_in", &OperatorOptions::entry_in, false},
    {"travel_height", &OperatorOptions::travel_height, false},
    {"above_height", &OperatorOptions::above_height, false},
    {"lift_height", &OperatorOptions::lift_height, false},
    {"rest_duration", &OperatorOptions::rest_duration, false},
    {"reach_duration", &OperatorOptions::reach_duration, false},
    {"entry_duration", &OperatorOptions::entry_duration, false},
    {"approach_duration", &OperatorOptions::approach_duration, false},
    {"descent_duration", &OperatorOptions::descent_duration, false},
    {"close_duration", &OperatorOptions::close_duration, false},
    {"settle_duration", &OperatorOptions::settle_duration, false},
    {"lift_duration", &OperatorOptions::lift_duration, false},
    {"hold_duration", &OperatorOptions::hold_duration, false},
    {"timing_spread", &OperatorOptions::timing_spread, false},
    {"position_noise", &OperatorOptions::position_noise, false},
    {"height_noise", &OperatorOptions::height_noise, false},
    {"yaw_noise_deg", &OperatorOptions::yaw_noise, true},
    {"path_noise", &OperatorOptions::path_noise, false},
    {"finger_noise_deg", &OperatorOptions::finger_noise, true},
    {"sloppy_fraction", &OperatorOptions::sloppy_fraction, false},
    {"sloppy_scale", &OperatorOptions::sloppy_scale, false},
};

constexpr ScalarField<GraspStyle> kStyleScalars[] = {
    {"hook_reach", &GraspStyle::hook_reach, false},
    {"wrist_above_handle", &GraspStyle::wrist_above_handle, false},
    {"max_pitch_deg", &GraspStyle::max_pitch, true},
    {"yaw_offset_deg", &GraspStyle::yaw_offset, true},
    {"roll_deg", &GraspStyle::roll, true},
};

// Reads the fields of `fields` present in `object` over `out` (degrees converted to rad).
template <class T, size_t N>
void ReadScalars(const JsonReader& object, const ScalarField<T> (&fields)[N], T* out) {
  for (const ScalarField<T>& f : fields) {
    if (const std::optional<double> v = object.OptionalNumber(f.name)) {
      out->*f.member = *v * (f.degrees ? kDeg : 1.0);
    }
  }
}

// Writes every field of `fields` of `in` into `j` (rad as degrees).
template <class T, size_t N>
void WriteScalars(const T& in, const ScalarField<T> (&fields)[N], json* j) {
  for (const ScalarField<T>& f : fields) (*j)[f.name] = in.*f.member / (f.degrees ? kDeg : 1.0);
}

// 16 joint angles in degrees, as rad.
HandVector HandDeg(const JsonReader& field) { return field.AsNumbers(kHandDof) * kDeg; }

// Reads the GraspStyle fields present in `object` over `style`.
void ReadStyle(const JsonReader& object, GraspStyle* style) {
  ReadScalars(object, kStyleScalars, style);
  if (const std::optional<double> v = object.OptionalNumber("thumb_close_duration")) {
    style->thumb_close_duration = *v;
  }
  if (object.Has("open_hand_deg")) style->open_hand = HandDeg(object.Field("open_hand_deg"));
  if (object.Has("closed_hand_deg")) style->closed_hand = HandDeg(object.Field("closed_hand_deg"));
}

void WriteStyle(const GraspStyle& style, json* j) {
  WriteScalars(style, kStyleScalars, j);
  // written only where it is used: the files made before it existed keep their bytes.
  if (style.thumb_close_duration != 0.0) {
    (*j)["thumb_close_duration"] = style.thumb_close_duration;
  }
  (*j)["open_hand_deg"] = HandToDeg(style.open_hand);
  (*j)["closed_hand_deg"] = HandToDeg(style.closed_hand);
}

// A strategy; its own grip starts from the top level's.
GraspStrategy ReadStrategy(const JsonReader& object, const GraspStyle& top_grasp) {
  object.AsObject();
  GraspStrategy g;
  g.weight = object.Number("weight");
  g.d = object.Number("d");
  g.eta_deg = object.Number("eta_deg");
  if (const std::optional<JsonReader> grasp = object.OptionalField("grasp")) {
    g.grasp = top_grasp;
    ReadStyle(grasp->AsObject(), &*g.grasp);
  }
  return g;
}

OrientationPlan ReadPlan(const JsonReader& object, const GraspStyle& top_grasp) {
  object.AsObject();
  OrientationPlan plan;
  plan.theta_deg = object.Number("theta_deg");
  plan.pregrasp_eta_deg = object.Number("pregrasp_eta_deg");
  if (object.Has("trials")) plan.trials = static_cast<int>(object.Integer("trials", 0, kMaxCount));
  for (const JsonReader& strategy : object.Array("strategies")) {
    plan.strategies.push_back(ReadStrategy(strategy, top_grasp));
  }
  return plan;
}

}  // namespace

HandVector GraspStyle::DefaultOpenHook() {
  HandVector f = HandVector::Zero();
  f.head<4>() << 0.0, 40.0 * kDeg, -10.0 * kDeg, 0.0;
  f[4] = -20.0 * kDeg;  // index spread toward the thumb
  f[10] = 20.0 * kDeg;  // ring and little the other way
  f[13] = 20.0 * kDeg;
  return f;
}

HandVector GraspStyle::DefaultClosedHook() {
  HandVector f = DefaultOpenHook();
  for (int finger = 0; finger < 4; ++finger) {
    f[5 + 3 * finger] = 15.0 * kDeg;  // MCP
    f[6 + 3 * finger] = 85.0 * kDeg;  // PIP (the DIP follows)
  }
  return f;
}

bool GraspStyle::IsValid(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  for (const ScalarField<GraspStyle>& f : kStyleScalars) {
    if (!std::isfinite(this->*f.member)) return fail(std::string(f.name) + " must be finite");
  }
  if (!(hook_reach > 0.0)) return fail("hook_reach must be > 0");
  if (!(thumb_close_duration >= 0.0 && std::isfinite(thumb_close_duration))) {
    return fail("thumb_close_duration must be finite and >= 0");
  }
  if (!(wrist_above_handle >= 0.0)) return fail("wrist_above_handle must be >= 0");
  if (!(max_pitch >= 0.0 && max_pitch < 0.5 * M_PI)) {
    return fail("max_pitch_deg must be in [0, 90)");
  }
  if (!open_hand.allFinite() || !closed_hand.allFinite()) return fail("hand shapes not finite");
  return true;
}

bool OperatorOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  if (trials_per_orientation < 1) return fail("trials_per_orientation must be >= 1");
  if (plans.empty()) return fail("there must be at least one orientation plan");
  for (const ScalarField<OperatorOptions>& f : kScalars) {
    const double v = this->*f.member;
    if (!std::isfinite(v) || (v < 0.0 && f.member != &OperatorOptions::rest_turn)) {
      return fail(std::string(f.name) + " must be finite and >= 0");
    }
  }
  if (!(sample_rate_hz >= 10.0 && sample_rate_hz <= 1000.0)) {
    return fail("sample_rate_hz must be in [10, 1000]");
  }
  std::string style_why;
  if (!grasp.IsValid(&style_why)) return fail(style_why);
  if (timing_spread >= 0.9) return fail("timing_spread must be < 0.9");
  if (sloppy_fraction > 1.0) return fail("sloppy_fraction must be <= 1");
  if (!(entry_out > entry_in)) return fail("entry_out must be larger than entry_in");
  for (double d :
       {rest_duration, reach_duration, entry_duration, approach_duration, descent_duration,
        close_duration, settle_duration, lift_duration, hold_duration}) {
    if (!(d > 0.0)) return fail("every duration must be > 0");
  }
  // the log's grasp mark needs a sample of its own before the last one (the end event).
  if ((lift_duration + hold_duration) * (1.0 - timing_spread) < 2.0 / sample_rate_hz) {
    std::ostringstream why;
    why << "lift_duration + hold_duration (" << lift_duration << " + " << hold_duration
        << " s, times 1 - timing_spread at the shortest) must last at least two samples (2 / "
           "sample_rate_hz = "
        << 2.0 / sample_rate_hz << " s), so that the grasp comes before the end of the trial";
    return fail(why.str());
  }
  for (const Eigen::Vector2d& p : positions) {
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > 5.0) {
      return fail("positions must be finite and within 5 m of the base");
    }
  }
  for (const OrientationPlan& p : plans) {
    const std::string at = "plan theta " + std::to_string(p.theta_deg);
    if (!std::isfinite(p.theta_deg) || !std::isfinite(p.pregrasp_eta_deg)) {
      return fail(at + ": angles must be finite");
    }
    if (p.strategies.empty()) return fail(at + ": needs at least one strategy");
    if (p.trials < 0) return fail(at + ": trials must be >= 0");
    for (const GraspStrategy& s : p.strategies) {
      if (!(s.weight > 0.0) || !std::isfinite(s.weight)) return fail(at + ": weight must be > 0");
      if (!(s.d > 0.0) || !std::isfinite(s.d) || !std::isfinite(s.eta_deg)) {
        return fail(at + ": strategy d must be > 0 and eta finite");
      }
      if (s.grasp && !s.grasp->IsValid(&style_why)) {
        return fail(at + ": strategy grasp: " + style_why);
      }
    }
  }
  return true;
}

namespace {

OperatorOptions ReadOperator(const JsonReader& document) {
  const JsonReader root = document.AsObject();
  root.ExpectString("format", kOperatorFormat);
  OperatorOptions o;
  if (root.Has("seed")) o.seed = root.Unsigned("seed");
  if (root.Has("trials_per_orientation")) {
    o.trials_per_orientation =
        static_cast<int>(root.Integer("trials_per_orientation", 1, kMaxCount));
  }
  ReadScalars(root, kScalars, &o);
  ReadStyle(root, &o.grasp);
  for (const JsonReader& plan : root.Array("plans")) o.plans.push_back(ReadPlan(plan, o.grasp));
  if (const auto positions = root.OptionalField("positions")) {
    for (const JsonReader& p : positions->AsArray()) {
      o.positions.emplace_back(p.AsNumbers(2, -5.0, 5.0));
    }
  }
  std::string why;
  if (!o.IsValid(&why)) throw InputError(root.source() + ": invalid operator options: " + why);
  return o;
}

}  // namespace

OperatorOptions ReadOperatorOptions(const std::filesystem::path& path) {
  return ReadOperator(JsonReader::Load(path, input_kind::kOperator));
}

OperatorOptions ParseOperatorOptions(std::string_view json_text, const std::string& source) {
  return ReadOperator(JsonReader::Parse(json_text, source));
}

void WriteOperatorOptions(const OperatorOptions& o, const std::filesystem::path& path) {
  json root;
  root["format"] = kOperatorFormat;
  root["comment"] =
      "The synthetic operator of learning_data/synthetic_operator.hpp: lengths in m, times in s, "
      "angles in deg. plans: per orientation, where the reach enters the grasp region and the "
      "intended wrist grasp positions (polar, around the object centre), calibrated with "
      "'graspsynth demos calibrate' so that the successful trials reproduce the paper's Table I.";
  root["seed"] = o.seed;
  root["trials_per_orientation"] = o.trials_per_orientation;
  WriteScalars(o, kScalars, &root);
  WriteStyle(o.grasp, &root);
  json plans = json::array();
  for (const OrientationPlan& p : o.plans) {
    json jp;
    jp["theta_deg"] = p.theta_deg;
    jp["pregrasp_eta_deg"] = p.pregrasp_eta_deg;
    jp["trials"] = p.trials;
    jp["strategies"] = json::array();
    for (const GraspStrategy& s : p.strategies) {
      json js = {{"weight", s.weight}, {"d", s.d}, {"eta_deg", s.eta_deg}};
      if (s.grasp) WriteStyle(*s.grasp, &js["grasp"]);
      jp["strategies"].push_back(js);
    }
    plans.push_back(jp);
  }
  root["plans"] = plans;
  if (!o.positions.empty()) {
    json positions = json::array();
    for (const Eigen::Vector2d& p : o.positions) positions.push_back({p.x(), p.y()});
    root["positions"] = positions;
  }
  WriteFileAtomically(path, root.dump(2) + "\n");
}

std::filesystem::path DefaultOperatorOptionsPath(const std::string& object_name) {
  return DefaultDemoDirectory(object_name) / "operator.json";
}

}  // namespace graspsynth
