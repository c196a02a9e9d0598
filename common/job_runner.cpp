#include "common/job_runner.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>

#include "common/atomic_file.hpp"
#include "common/byte_codec.hpp"
#include "common/demand.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/json_reader.hpp"
#include "common/parallel.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;

constexpr const char* kResumeFormat = "graspsynth-resume/2";
constexpr const char* kJobFormat = "graspsynth-job/2";
// How many reasons for recomputed jobs a summary keeps.
constexpr size_t kReasonsKept = 5;

std::string Quoted(const std::string& s) { return "'" + s + "'"; }

// Throws InputError naming the first difference between the earlier run's identity (the
// folder's run.json) and this run's.
void CheckSameRun(const fs::path& manifest, const RunIdentity& now) {
  const std::string refuse =
      "--resume: the unfinished run in '" + manifest.parent_path().string() + "' was started ";
  const std::string other_build =
      " (its kept jobs are results of that build; start afresh without --resume, or resume it "
      "with the program that started it)";
  const JsonReader doc = JsonReader::Load(manifest).AsObject();
  const std::string format = doc.String("format");
  if (format != kResumeFormat) {
    throw InputError(refuse + "by another version of graspsynth (its run.json is " +
                     Quoted(format) + ", this version writes " + Quoted(kResumeFormat) + ")" +
                     other_build);
  }
  const std::string build = doc.String("build");
  if (build != BuildId()) {
    throw InputError(refuse + "by " + Quoted(build) + ", not by this build, " +
                     Quoted(std::string(BuildId())) + other_build);
  }
  const std::string afresh = " (start afresh without --resume, or give the same ones)";
  const std::string command = doc.String("command");
  if (command != now.command) {
    throw InputError(refuse + "by the command " + Quoted(command) + ", not " + Quoted(now.command) +
                     afresh);
  }
  std::vector<std::pair<std::string, std::string>> before;
  for (const JsonReader& f : doc.Array("fields")) {
    before.emplace_back(f.String("name"), f.String("value"));
  }
  // the value of `name` among `fields`, if any.
  const auto find = [](const std::vector<std::pair<std::string, std::string>>& fields,
                       const std::string& name) -> const std::string* {
    for (const auto& f : fields) {
      if (f.first == name) return &f.second;
    }
    return nullptr;
  };
  for (const auto& [name, value] : now.fields) {
    const std::string* earlier = find(before, name);
    if (!earlier) {
      throw InputError(refuse + "without " + name + " (now " + Quoted(value) + ")" + afresh);
    }
    if (*earlier != value) {
      throw InputError(refuse + "with " + name + " " + Quoted(*earlier) + ", now " + Quoted(value) +
                       afresh);
    }
  }
  for (const auto& [name, value] : before) {
    if (!find(now.fields, name)) {
      throw InputError(refuse + "with " + name + " " + Quoted(value) + ", now without it" + afresh);
    }
  }
}

std::string IdentityJson(const RunIdentity& identity) {
  nlohmann::ordered_json j;
  j["format"] = kResumeFormat;
  j["build"] = BuildId();
  j["command"] = identity.command;
  j["fields"] = nlohmann::ordered_json::array();
  for (const auto& [name, value] : identity.fields) {
    j["fields"].push_back({{"name", name}, {"value", value}});
  }
  return j.dump(2) + "\n";
}

// The 64-bit FNV-1a fingerprint (as Fingerprint writes it) of the file that holds this code: the
// executable, or the shared library (Python's module) it was linked into; "" when it cannot be
// found or read.
std::string FingerprintOfThisCode() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<const void*>(&FingerprintOfThisCode), &info) == 0 ||
      info.dli_fname == nullptr) {
    return "";
  }
  std::ifstream in(info.dli_fname, std::ios::binary);
  if (!in) return "";
  // read in pieces: a sanitizer build's test binary has hundreds of megabytes.
  std::string piece(1 << 20, '\0');
  FingerprintState state;
  while (in.read(piece.data(), static_cast<std::streamsize>(piece.size())) || in.gcount() > 0) {
    state.Add(std::string_view(piece.data(), static_cast<size_t>(in.gcount())));
  }
  return in.bad() ? "" : state.Hex();
}

}  // namespace

std::string_view BuildId() {
  static const std::string id = [] {
    const std::string code = FingerprintOfThisCode();
    return std::string("graspsynth ") + GRASPSYNTH_VERSION +
           (code.empty() ? std::string() : ", build " + code);
  }();
  return id;
}

RunIdentity& RunIdentity::AddFile(std::string name, const fs::path& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec))
    return Add(std::move(name), Fingerprint(ReadInputFile(path, input_kind::kFingerprinted)));
  std::vector<fs::path> files;
  for (fs::recursive_directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec)) files.push_back(it->path());
  }
  if (ec) throw InputError("cannot list '" + path.string() + "': " + ec.message());
  std::sort(files.begin(), files.end());
  std::string listing;
  for (const fs::path& f : files) {
    listing += f.lexically_relative(path).generic_string() + " " +
               Fingerprint(ReadInputFile(f, input_kind::kFingerprinted)) + "\n";
  }
  return Add(std::move(name), Fingerprint(listing));
}

ResumeFolder::ResumeFolder(fs::path folder, const RunIdentity& identity, bool resume)
    : folder_(std::move(folder)) {
  const fs::path manifest = folder_ / "run.json";
  std::error_code ec;
  if (resume && fs::exists(manifest, ec)) {
    CheckSameRun(manifest, identity);
    resumed_ = true;
    return;
  }
  fs::remove_all(folder_, ec);
  if (ec) {
    throw InputError("cannot clear the resume folder '" + folder_.string() + "': " + ec.message());
  }
  WriteFileAtomically(manifest, IdentityJson(identity));
}

fs::path ResumeFolder::JobPath(const std::string& stage, int index) const {
  return folder_ / stage / (std::to_string(index) + ".job");
}

std::string JobFileBytes(const JobFile& job) {
  ByteWriter w;
  w.String(kJobFormat);
  w.String(job.build);
  w.String(job.stage);
  w.Int(job.index);
  w.String(job.payload);
  w.String(Fingerprint(job.result));
  w.String(job.result);
  return w.Take();
}

JobFile ParseJobFile(std::string_view bytes, const std::string& source) {
  ByteReader r(bytes, source);
  const std::string format = r.String();
  if (format != kJobFormat) {
    throw InputError(source + ": not a " + kJobFormat + " file (format '" + format + "')");
  }
  JobFile job;
  job.build = r.String();
  job.stage = r.String();
  job.index = r.Int();
  job.payload = r.String();
  const std::string checksum = r.String();
  job.result = r.String();
  r.Finish();
  if (Fingerprint(job.result) != checksum) {
    throw InputError(source + ": the result's checksum is " + Fingerprint(job.result) +
                     ", the file says " + checksum + " (the result was changed or damaged)");
  }
  return job;
}

std::optional<std::string> ResumeFolder::Load(const JobStage& stage, int index) const {
  const fs::path path = JobPath(stage.name, index);
  std::error_code ec;
  if (!fs::exists(path, ec) && !fs::is_symlink(path, ec)) return std::nullopt;
  const std::string name = stage.name + "/" + std::to_string(index) + ".job";
  std::string rejected;
  try {
    JobFile job = ParseJobFile(ReadInputFile(path, input_kind::kResumeJob), name);
    if (job.build != BuildId()) {
      rejected = name + ": made by " + Quoted(job.build) + ", not by this build";
    } else if (job.stage != stage.name || job.index != index) {
      rejected =
          name + ": holds job " + std::to_string(job.index) + " of stage " + Quoted(job.stage);
    } else if (job.payload != stage.payload) {
      rejected =
          name + ": a result of layout " + Quoted(job.payload) + ", not " + Quoted(stage.payload);
    } else {
      try {
        if (stage.check) stage.check(index, job.result);
        std::lock_guard<std::mutex> lock(mutex_);
        ++summary_.taken;
        return std::move(job.result);
      } catch (const InputError& e) {
        rejected = name + ": " + e.what();  // a result the stage cannot decode
      }
    }
  } catch (const InputError& e) {
    rejected = e.what();  // a damaged file (the message names it): the job runs again
  }
  std::lock_guard<std::mutex> lock(mutex_);
  ++summary_.recomputed;
  if (summary_.reasons.size() < kReasonsKept) summary_.reasons.push_back(rejected);
  return std::nullopt;
}

void ResumeFolder::Save(const JobStage& stage, int index, std::string_view bytes) const {
  WriteFileAtomically(
      JobPath(stage.name, index),
      JobFileBytes({std::string(BuildId()), stage.name, index, stage.payload, std::string(bytes)}));
}

ResumeSummary ResumeFolder::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return summary_;
}

void ResumeFolder::Remove() const {
  std::error_code ec;
  fs::remove_all(folder_, ec);
}

void DemandValidStage(const JobStage& stage) {
  GS_DEMAND(
      !stage.name.empty() && std::all_of(stage.name.begin(), stage.name.end(),
                                         [](char c) {
                                           return std::isalnum(static_cast<unsigned char>(c)) ||
                                                  c == '-' || c == '_';
                                         }),
      "a job stage's name is letters, digits, '-' and '_'");
  GS_DEMAND(stage.count >= 0, "a job stage has a count >= 0");
  GS_DEMAND(static_cast<bool>(stage.run), "a job stage has a job function");
}

StageResults::StageResults(const JobStage& stage, const ResumeFolder* resume)
    : stage_(stage), resume_(resume), results_(static_cast<size_t>(stage.count)) {
  DemandValidStage(stage);
  for (int i = 0; i < stage.count; ++i) {
    std::optional<std::string> kept = resume ? resume->Load(stage, i) : std::nullopt;
    if (kept) {
      Keep(i, std::move(*kept), false, false);
    } else {
      todo_.push_back(i);
    }
  }
}

void StageResults::Add(int i, std::string bytes, bool here) {
  Keep(i, std::move(bytes), here, true);
}

void StageResults::Keep(int i, std::string bytes, bool here, bool save) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (save && resume_) resume_->Save(stage_, i, bytes);
  results_[static_cast<size_t>(i)] = std::move(bytes);
  if (stage_.finished) stage_.finished(i, here);
}

std::vector<std::string> LocalJobRunner::Run(const JobStage& stage) {
  StageResults results(stage, resume_folder());
  const std::vector<int>& todo = results.todo();
  ParallelFor(static_cast<int>(todo.size()), stage.threads, [&](int k) {
    const int i = todo[static_cast<size_t>(k)];
    results.Add(i, stage.run(i), true);
  });
  return results.Take();
}

}  // namespace graspsynth
