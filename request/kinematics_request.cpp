#include "request/kinematics_request.hpp"

#include <utility>

namespace graspsynth::request {
namespace {

using R = IkRequest;

OptionList<R> MakeOptions() {
  OptionInfo branch =
      MakeInfo("branch", OptionKind::kNumbers,
               "Only this branch: the signs of S2, E1, W1 as GC2,GC4,GC6, e.g. 1,1,-1");
  branch.placeholder = "GC2,GC4,GC6";
  Option<R> o = OptionalVectorOption<R, 3>(
      branch, [](R& r) -> std::optional<Eigen::Vector3i>& { return r.branch; });
  o.check = [](const Value& value, const std::string& where) {
    for (double v : std::get<std::vector<double>>(value)) {
      if (v != 1.0 && v != -1.0) {
        throw InputError(where + " takes three signs GC2,GC4,GC6, each 1 or -1, got '" +
                         ShowValue(MakeInfo("branch", OptionKind::kNumbers, ""), value) + "'");
      }
    }
  };
  OptionList<R> list;
  list.push_back(std::move(o));
  return list;
}

}  // namespace

const OptionList<IkRequest>& IkOptions() {
  static const OptionList<IkRequest> options = MakeOptions();
  return options;
}

}  // namespace graspsynth::request
