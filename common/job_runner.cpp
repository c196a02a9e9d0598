#include "common/job_runner.hpp"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>

#include "common/atomic_file.hpp"
#include "common/byte_codec.hpp"
#include "common/demand.hpp"
#include "common/errors.hpp"
#include "common/json_reader.hpp"
#include "common/parallel.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;

constexpr const char* kResumeFormat = "graspsynth-resume/1";
constexpr const char* kJobFormat = "graspsynth-job/1";

std::string ReadFileOrThrow(const fs::path& path) {
  std::optional<std::string> bytes = ReadWholeFile(path);
  if (!bytes) throw InputError("cannot read '" + path.string() + "'");
  return std::move(*bytes);
}

std::string Quoted(const std::string& s) { return "'" + s + "'"; }

// Throws InputError naming the first difference between the earlier run's identity (the
// folder's run.json) and this run's.
void CheckSameRun(const fs::path& manifest, const RunIdentity& now) {
  const JsonReader doc = JsonReader::Load(manifest).AsObject();
  doc.ExpectString("format", kResumeFormat);
  const std::string refuse =
      "--resume: the unfinished run in '" + manifest.parent_path().string() + "' was started ";
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
  j["command"] = identity.command;
  j["fields"] = nlohmann::ordered_json::array();
  for (const auto& [name, value] : identity.fields) {
    j["fields"].push_back({{"name", name}, {"value", value}});
  }
  return j.dump(2) + "\n";
}

}  // namespace

RunIdentity& RunIdentity::AddFile(std::string name, const fs::path& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return Add(std::move(name), Fingerprint(ReadFileOrThrow(path)));
  std::vector<fs::path> files;
  for (fs::recursive_directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec)) files.push_back(it->path());
  }
  if (ec) throw InputError("cannot list '" + path.string() + "': " + ec.message());
  std::sort(files.begin(), files.end());
  std::string listing;
  for (const fs::path& f : files) {
    listing +=
        f.lexically_relative(path).generic_string() + " " + Fingerprint(ReadFileOrThrow(f)) + "\n";
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
  w.String(job.stage);
  w.Int(job.index);
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
  job.stage = r.String();
  job.index = r.Int();
  job.result = r.String();
  r.Finish();
  return job;
}

std::optional<std::string> ResumeFolder::Load(const std::string& stage, int index) const {
  const fs::path path = JobPath(stage, index);
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  try {
    JobFile job = ParseJobFile(ReadFileOrThrow(path), path.string());
    if (job.stage != stage || job.index != index) return std::nullopt;
    return std::move(job.result);
  } catch (const InputError&) {
    return std::nullopt;  // a damaged file: the job runs again
  }
}

void ResumeFolder::Save(const std::string& stage, int index, std::string_view bytes) const {
  WriteFileAtomically(JobPath(stage, index), JobFileBytes({stage, index, std::string(bytes)}));
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
    std::optional<std::string> kept = resume ? resume->Load(stage.name, i) : std::nullopt;
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
  if (save && resume_) resume_->Save(stage_.name, i, bytes);
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
