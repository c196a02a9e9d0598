#include "common/json_reader.hpp"
#include "common/input_file.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

using Json = nlohmann::ordered_json;

// Bare non-finite tokens are turned into strings that start with this mark, so that the number
// checks can name the field holding them instead of the parser reporting a byte offset.
constexpr std::string_view kNonFiniteMark = "\x01non-finite:";

std::string MarkNonFiniteTokens(std::string_view text) {
  static constexpr std::string_view kTokens[] = {"-Infinity", "Infinity", "-NaN", "NaN",
                                                 "-nan",      "nan",      "-inf", "inf"};
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      out += c;
      continue;
    }
    bool replaced = false;
    for (std::string_view token : kTokens) {
      if (text.substr(i, token.size()) == token) {
        out += "\"\\u0001non-finite:";  // parses to kNonFiniteMark
        out += token;
        out += '"';
        i += token.size() - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += c;
  }
  return out;
}

const Json& Value(const void* node) { return *static_cast<const Json*>(node); }

std::string Range(double lo, double hi) {
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

}  // namespace

struct JsonReader::Document {
  std::string source;
  Json root;
};

JsonReader::JsonReader(std::shared_ptr<const Document> document, const void* node, std::string path)
    : document_(std::move(document)), node_(node), path_(std::move(path)) {}

const std::string& JsonReader::source() const { return document_->source; }

JsonReader JsonReader::Child(const void* node, std::string path) const {
  return JsonReader(document_, node, std::move(path));
}

JsonReader JsonReader::Parse(std::string_view text, const std::string& source) {
  auto document = std::make_shared<Document>();
  document->source = source;
  try {
    document->root = Json::parse(MarkNonFiniteTokens(text));
  } catch (const Json::exception& e) {  // parse_error, and out_of_range for 1e999
    std::string what = e.what();
    if (const size_t end = what.find("] ");
        what.rfind("[json.exception", 0) == 0 && end != what.npos) {
      what = what.substr(end + 2);
    }
    throw InputError(source + ": not valid JSON: " + what);
  }
  const void* root = &document->root;
  return JsonReader(std::move(document), root, "");
}

JsonReader JsonReader::Load(const std::filesystem::path& path, const InputFileKind& kind) {
  return Parse(ReadInputFile(path, kind), path.string());
}

std::string JsonReader::Shown() const {
  if (!node_) return "nothing";
  const Json& v = Value(node_);
  if (v.is_string()) {
    const std::string& s = v.get_ref<const std::string&>();
    if (s.rfind(kNonFiniteMark, 0) == 0) return s.substr(kNonFiniteMark.size());
  }
  std::string text = v.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

void JsonReader::Fail(std::string_view expected) const {
  const std::string where = path_.empty() ? "the document" : "field '" + path_ + "'";
  throw InputError(source() + ": " + where + ": expected " + std::string(expected) + ", found " +
                   Shown());
}

bool JsonReader::IsObject() const { return node_ && Value(node_).is_object(); }
bool JsonReader::IsArray() const { return node_ && Value(node_).is_array(); }
bool JsonReader::IsString() const {
  return node_ && Value(node_).is_string() &&
         Value(node_).get_ref<const std::string&>().rfind(kNonFiniteMark, 0) != 0;
}
bool JsonReader::IsNumber() const { return node_ && Value(node_).is_number(); }
bool JsonReader::IsNull() const { return node_ && Value(node_).is_null(); }

const JsonReader& JsonReader::AsObject() const {
  if (!IsObject()) Fail("an object");
  return *this;
}

void JsonReader::RequireObject() const {
  if (!IsObject()) Fail("an object");
}

double JsonReader::AsNumber() const {
  if (!IsNumber() || !std::isfinite(Value(node_).get<double>())) Fail("a finite number");
  return Value(node_).get<double>();
}

double JsonReader::AsNumberIn(double lo, double hi) const {
  const std::string expected = "a number in " + Range(lo, hi);
  if (!IsNumber()) Fail(expected);
  const double x = Value(node_).get<double>();
  if (!(x >= lo && x <= hi)) Fail(expected);
  return x;
}

double JsonReader::AsPositiveNumber() const {
  if (!IsNumber()) Fail("a number > 0");
  const double x = Value(node_).get<double>();
  if (!(x > 0.0) || !std::isfinite(x)) Fail("a finite number > 0");
  return x;
}

int64_t JsonReader::AsInteger(int64_t lo, int64_t hi) const {
  const std::string expected =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!node_ || !Value(node_).is_number_integer()) Fail(expected);
  const Json& v = Value(node_);
  if (v.is_number_unsigned() &&
      v.get<uint64_t>() > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
    Fail(expected);
  }
  const int64_t x = v.get<int64_t>();
  if (x < lo || x > hi) Fail(expected);
  return x;
}

uint64_t JsonReader::AsUnsigned() const {
  if (!node_ || !Value(node_).is_number_unsigned()) Fail("a non-negative integer");
  return Value(node_).get<uint64_t>();
}

bool JsonReader::AsBool() const {
  if (!node_ || !Value(node_).is_boolean()) Fail("true or false");
  return Value(node_).get<bool>();
}

std::string JsonReader::AsString() const {
  if (!IsString()) Fail("a string");
  return Value(node_).get<std::string>();
}

std::vector<JsonReader> JsonReader::AsArray() const {
  if (!IsArray()) Fail("an array");
  std::vector<JsonReader> elements;
  const Json& v = Value(node_);
  elements.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    elements.push_back(Child(&v[i], path_ + "[" + std::to_string(i) + "]"));
  }
  return elements;
}

Eigen::VectorXd JsonReader::AsNumbers(int count, double lo, double hi) const {
  const bool bounded = std::isfinite(lo) || std::isfinite(hi);
  const std::string each = bounded ? "numbers in " + Range(lo, hi) : "finite numbers";
  if (!IsArray() || Value(node_).size() != static_cast<size_t>(count)) {
    Fail("an array of " + std::to_string(count) + " " + each);
  }
  const std::vector<JsonReader> elements = AsArray();
  Eigen::VectorXd x(count);
  for (int i = 0; i < count; ++i) {
    x[i] = bounded ? elements[i].AsNumberIn(lo, hi) : elements[i].AsNumber();
  }
  return x;
}

bool JsonReader::Has(std::string_view key) const {
  RequireObject();
  return Value(node_).contains(key);
}

std::vector<std::string> JsonReader::Keys() const {
  RequireObject();
  std::vector<std::string> keys;
  for (const auto& item : Value(node_).items()) keys.push_back(item.key());
  return keys;
}

void JsonReader::RejectUnknownKeys(std::initializer_list<std::string_view> known) const {
  for (const std::string& key : Keys()) {
    bool found = false;
    for (std::string_view k : known) found = found || k == key;
    if (found) continue;
    std::string names;
    for (std::string_view k : known) {
      if (!names.empty()) names += ", ";
      names += k;
    }
    Field(key).Fail("only the fields " + names + " here");
  }
}

JsonReader JsonReader::Field(std::string_view key) const {
  RequireObject();
  const std::string path = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  const Json& v = Value(node_);
  const auto it = v.find(key);
  return Child(it == v.end() ? nullptr : &*it, path);
}

std::optional<JsonReader> JsonReader::OptionalField(std::string_view key) const {
  JsonReader field = Field(key);
  if (!field.present()) return std::nullopt;
  return field;
}

void JsonReader::ExpectString(std::string_view key, std::string_view expected) const {
  const JsonReader field = Field(key);
  if (!field.IsString() || field.AsString() != expected) {
    field.Fail("\"" + std::string(expected) + "\"");
  }
}

Eigen::Vector3d JsonReader::Vector3(std::string_view key) const { return Numbers(key, 3); }

Eigen::Quaterniond JsonReader::Quaternion(std::string_view key) const {
  const Eigen::VectorXd q = Numbers(key, 4);
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

Eigen::Quaterniond JsonReader::UnitQuaternion(std::string_view key, double tolerance) const {
  const Eigen::Quaterniond q = Quaternion(key);
  if (std::abs(q.norm() - 1.0) > tolerance) {
    std::ostringstream expected;
    expected << "a unit quaternion [w, x, y, z] (norm within " << tolerance << " of 1; norm "
             << q.norm() << ")";
    Field(key).Fail(expected.str());
  }
  return q;
}

std::optional<double> JsonReader::OptionalNumber(std::string_view key) const {
  const std::optional<JsonReader> field = OptionalField(key);
  if (!field) return std::nullopt;
  return field->AsNumber();
}

}  // namespace graspsynth
