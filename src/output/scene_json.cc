// Writes scenes as spec §8 JSON, keys in the order the spec lists them: objects in creation
// order, quaternions (w, x, y, z) mapping local to world, yaw/pitch/roll, dimensions, and the
// other properties in definition order. Written directly (this is the hot path of `prs
// sample`): numbers from fmt's shortest digits, strings that need escaping through
// nlohmann-json, and the parts of kept objects that every scene repeats from text made once.
#include "output/scene_json.h"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

#include "geometry/rotation.h"

namespace prs::output {
namespace {

using Out = std::string;

// "00" "01" ... "99": two digits at a time.
constexpr auto kDigitPairs = [] {
  std::array<char, 200> pairs{};
  for (int i = 0; i < 100; ++i) {
    pairs[2 * i] = char('0' + i / 10);
    pairs[2 * i + 1] = char('0' + i % 10);
  }
  return pairs;
}();

// n < 10^8 as exactly eight digits: two independent halves of four, two digits a step.
void WriteEightDigits(uint32_t n, char* out) {
  const uint32_t high = n / 10000, low = n % 10000;
  std::memcpy(out, &kDigitPairs[2 * (high / 100)], 2);
  std::memcpy(out + 2, &kDigitPairs[2 * (high % 100)], 2);
  std::memcpy(out + 4, &kDigitPairs[2 * (low / 100)], 2);
  std::memcpy(out + 6, &kDigitPairs[2 * (low % 100)], 2);
}

// A significand has at most 17 digits; eight at a time, three groups fit it.
constexpr int kSignificandChars = 24;

// The decimal digits of n > 0 at the end of `digits`; returns the first. Eight digits at a
// time, as the digit-at-a-time loop's chain of 64-bit divisions was most of the writer's time.
const char* WriteSignificand(uint64_t n, char (&digits)[kSignificandChars]) {
  char* first = digits + kSignificandChars;
  while (n >= 100000000) {
    first -= 8;
    WriteEightDigits(static_cast<uint32_t>(n % 100000000), first);
    n /= 100000000;
  }
  first -= 8;
  WriteEightDigits(static_cast<uint32_t>(n), first);  // 1 <= n < 10^8: ends the zeros
  while (*first == '0') ++first;
  return first;
}

}  // namespace

// fmt's "{}" for a finite double, written from fmt's own shortest digits (Dragonbox) without
// fmt's general float writer, which handles padding, locales and precisions that "{}" never
// uses. The layout is fmt's: fixed notation for decimal exponents in [-4, 16), else d.ddde±XX.
char* WriteShortest(double x, char* out) {
  if (std::signbit(x)) {
    *out++ = '-';
    x = -x;
  }
  if (x == 0) {
    *out++ = '0';
    return out;
  }
  const auto decimal = fmt::detail::dragonbox::to_decimal(x);
  char digits[kSignificandChars];
  const char* first = WriteSignificand(decimal.significand, digits);
  const int size = static_cast<int>(digits + kSignificandChars - first);
  const int output_exp = decimal.exponent + size - 1;
  if (output_exp < -4 || output_exp >= 16) {
    *out++ = first[0];
    if (size > 1) {
      *out++ = '.';
      out = std::copy(first + 1, first + size, out);
    }
    *out++ = 'e';
    *out++ = output_exp < 0 ? '-' : '+';
    const int e = output_exp < 0 ? -output_exp : output_exp;
    if (e >= 100) {
      if (e >= 1000) *out++ = char('0' + e / 1000);
      *out++ = char('0' + e / 100 % 10);
    }
    *out++ = char('0' + e / 10 % 10);
    *out++ = char('0' + e % 10);
    return out;
  }
  const int point = decimal.exponent + size;  // digits before the decimal point
  if (decimal.exponent >= 0) {                // 1234e5 -> 123400000
    out = std::copy(first, first + size, out);
    return std::fill_n(out, decimal.exponent, '0');
  }
  if (point > 0) {  // 1234e-2 -> 12.34
    out = std::copy(first, first + point, out);
    *out++ = '.';
    return std::copy(first + point, first + size, out);
  }
  *out++ = '0';  // 1234e-6 -> 0.001234
  *out++ = '.';
  out = std::fill_n(out, -point, '0');
  return std::copy(first, first + size, out);
}

namespace {

// Shortest round-trip digits; integral values keep a ".0" so readers see a float, and
// non-finite values (never produced for positions) become null as JSON has no spelling for them.
char* WriteNumber(double x, char* out) {
  if (!std::isfinite(x)) return std::copy_n("null", 4, out);
  // Whole numbers (most dimensions, quaternion parts, zeros) are common: print them as integers.
  if (x == std::trunc(x) && std::abs(x) < 1e15) {
    if (std::signbit(x)) *out++ = '-';
    out = std::to_chars(out, out + 24, static_cast<int64_t>(std::abs(x))).ptr;
    return std::copy_n(".0", 2, out);
  }
  char* const start = out;
  out = WriteShortest(x, out);
  // A number with a fractional part always shows a '.' or an exponent; only a whole number
  // too large for the branch above may lack both.
  if (x == std::trunc(x) &&
      std::string_view(start, out - start).find_first_of(".e") == std::string_view::npos) {
    out = std::copy_n(".0", 2, out);
  }
  return out;
}

// Room for the longest text WriteNumber writes (24 characters: a sign, 17 digits, a point and
// an exponent such as "e-308").
constexpr size_t kMaxNumberChars = 32;

void AppendNumber(double x, Out& out) {
  char text[kMaxNumberChars];
  out.append(text, WriteNumber(x, text));
}

bool IsPlainAscii(std::string_view s) {
  for (const char c : s) {
    if (c < 0x20 || c == 0x7f || c == '"' || c == '\\' || static_cast<unsigned char>(c) >= 0x80) {
      return false;
    }
  }
  return true;
}

// Escapes as JSON requires; invalid UTF-8 is replaced by U+FFFD rather than failing.
void AppendString(std::string_view s, Out& out) {
  if (IsPlainAscii(s)) {
    out += '"';
    out += s;
    out += '"';
    return;
  }
  out +=
      nlohmann::json(std::string(s)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// `[x,y,...]`, written to the stack and appended once (at most four numbers here).
void AppendNumbers(std::initializer_list<double> numbers, Out& out) {
  char text[2 + 4 * (kMaxNumberChars + 1)];
  if (numbers.size() > 4) throw std::logic_error("AppendNumbers: at most four numbers");
  char* end = text;
  *end++ = '[';
  for (const double x : numbers) {
    if (end != text + 1) *end++ = ',';
    end = WriteNumber(x, end);
  }
  *end++ = ']';
  out.append(text, end);
}

void AppendValue(const lang::Value& v, Out& out);

void AppendElements(const std::vector<lang::Value>& items, Out& out) {
  out += '[';
  for (size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += ',';
    AppendValue(items[i], out);
  }
  out += ']';
}

// Numbers, booleans, strings, vectors, tuples and lists as JSON; None as null; any other
// value (a region, a class, ...) as its short description, a string.
void AppendValue(const lang::Value& v, Out& out) {
  const auto& data = v.data;
  if (const auto* x = std::get_if<double>(&data)) return AppendNumber(*x, out);
  if (const auto* b = std::get_if<bool>(&data)) {
    out += *b ? "true" : "false";
    return;
  }
  if (const auto* s = std::get_if<lang::StringPtr>(&data)) return AppendString(**s, out);
  if (const auto* p = std::get_if<Eigen::Vector3d>(&data))
    return AppendNumbers({p->x(), p->y(), p->z()}, out);
  if (v.Is<lang::NoneValue>()) {
    out += "null";
    return;
  }
  if (const auto* t = std::get_if<std::shared_ptr<lang::TupleData>>(&data))
    return AppendElements((*t)->elements, out);
  if (const auto* l = std::get_if<std::shared_ptr<lang::ListData>>(&data))
    return AppendElements((*l)->elements, out);
  if (const auto* m = std::get_if<lang::MeshRef>(&data)) {
    // A mesh shape: the file as the program names it, where it was read, and its scale.
    out += "{\"mesh\":";
    AppendString(m->mesh->name, out);
    out += ",\"path\":";
    AppendString(m->mesh->path, out);
    out += ",\"scale\":";
    AppendNumber(m->scale, out);
    out += '}';
    return;
  }
  if (const auto* p = std::get_if<lang::PrimitiveRef>(&data)) {
    // A built-in shape: its kind; its size is the object's dimensions.
    out += "{\"primitive\":";
    AppendString(shapes::PrimitiveName(p->kind), out);
    out += '}';
    return;
  }
  AppendString(lang::Repr(v), out);
}

void AppendProperties(const lang::SceneObject& o, Out& out) {
  out += '{';
  bool first = true;
  for (const auto& [name, value] : o.properties) {
    if (IsCoreProperty(name)) continue;
    if (!first) out += ',';
    first = false;
    AppendString(name, out);
    out += ':';
    AppendValue(value, out);
  }
  out += '}';
}

// `"quaternion":[...],"yaw_pitch_roll":[...]` for the orientation R_WO.
void AppendOrientation(const Eigen::Quaterniond& R_WO, Out& out) {
  const Eigen::Matrix3d R = R_WO.toRotationMatrix();
  const Eigen::Quaterniond q = geometry::CanonicalQuaternion(R);
  const Eigen::Vector3d ypr = geometry::CalcYawPitchRoll(R);
  out += "\"quaternion\":";
  AppendNumbers({q.w(), q.x(), q.y(), q.z()}, out);
  out += ",\"yaw_pitch_roll\":";
  AppendNumbers({ypr.x(), ypr.y(), ypr.z()}, out);
}

// Most objects keep the world's axes: their orientation's text is made once, by the same code.
bool IsExactIdentity(const Eigen::Quaterniond& q) {
  return q.w() == 1 && q.x() == 0 && q.y() == 0 && q.z() == 0 && !std::signbit(q.x()) &&
         !std::signbit(q.y()) && !std::signbit(q.z());
}

void AppendObjectOrientation(const Eigen::Quaterniond& R_WO, Out& out) {
  static const std::string kIdentity = [] {
    std::string text;
    AppendOrientation(Eigen::Quaterniond::Identity(), text);
    return text;
  }();
  if (IsExactIdentity(R_WO)) {
    out += kIdentity;
  } else {
    AppendOrientation(R_WO, out);
  }
}

// `{"name":...,"class":...,"position":[...],` — the part of an object's text that differs
// between copies of one template (SceneObject::template_id).
void AppendObjectHead(const lang::SceneObject& o, Out& out) {
  out += "{\"name\":";
  if (o.name) {
    AppendString(*o.name, out);
  } else {
    out += "null";
  }
  out += ",\"class\":";
  AppendString(o.cls->name, out);
  out += ",\"position\":";
  AppendNumbers({o.p_WO.x(), o.p_WO.y(), o.p_WO.z()}, out);
  out += ',';
}

// `"orientation":{...},"dimensions":[...],"properties":{...}}`: the rest.
void AppendObjectTail(const lang::SceneObject& o, Out& out) {
  out += "\"orientation\":{";
  AppendObjectOrientation(o.R_WO, out);
  out += "},\"dimensions\":";
  AppendNumbers({o.dimensions.x(), o.dimensions.y(), o.dimensions.z()}, out);
  out += ",\"properties\":";
  AppendProperties(o, out);
  out += '}';
}

// Objects a sampler keeps have text made once per thread, by the same code: an object copied
// unchanged into every scene (SceneObject::fixed_id) all of it, a copy of a template
// (SceneObject::template_id) all but its head. Ids are never shared between kept objects, so
// one table holds both. At most kMaxKept texts are kept (a process that makes many samplers
// starts over).
void AppendObject(const lang::SceneObject& o, Out& out) {
  const uint64_t id = o.fixed_id != 0 ? o.fixed_id : o.template_id;
  if (id == 0) {
    AppendObjectHead(o, out);
    AppendObjectTail(o, out);
    return;
  }
  constexpr size_t kMaxKept = 4096;
  thread_local std::unordered_map<uint64_t, std::string> texts;
  auto it = texts.find(id);
  if (it == texts.end()) {
    if (texts.size() >= kMaxKept) texts.clear();
    std::string text;
    if (o.fixed_id != 0) AppendObjectHead(o, text);
    AppendObjectTail(o, text);
    it = texts.emplace(id, std::move(text)).first;
  }
  if (o.fixed_id == 0) AppendObjectHead(o, out);
  out += it->second;
}

void AppendHeader(const sampling::SampledScene& sampled, Out& out) {
  fmt::format_to(std::back_inserter(out),
                 FMT_COMPILE("{{\"format\":\"prs-scene/1\",\"seed\":{},\"index\":{},"
                             "\"attempts\":{},\"rejections\":{{"),
                 sampled.seed, sampled.index, sampled.attempts);
  bool first = true;
  for (const auto& [kind, n] : sampled.rejections.by_kind) {
    fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}\"{}\":{}"), first ? "" : ",",
                   lang::RejectionKindName(kind), n);
    first = false;
  }
  out += '}';
  // --settle: the simulated seconds the free bodies took to come to rest (docs/physics.md).
  if (sampled.scene.settled_s) {
    fmt::format_to(std::back_inserter(out), FMT_COMPILE(",\"settled_s\":{:.3f}"),
                   *sampled.scene.settled_s);
  }
}

void AppendParams(const lang::Scene& scene, Out& out) {
  out += ",\"params\":{";
  for (size_t i = 0; i < scene.params.size(); ++i) {
    if (i > 0) out += ',';
    AppendString(scene.params[i].first, out);
    out += ':';
    AppendValue(scene.params[i].second, out);
  }
  out += '}';
}

}  // namespace

// string_view comparisons check the length first, so most names are rejected without memcmp.
bool IsCoreProperty(std::string_view name) {
  using namespace std::literals;
  return name == "position"sv || name == "orientation"sv || name == "width"sv ||
         name == "length"sv || name == "height"sv || name == "yaw"sv || name == "pitch"sv ||
         name == "roll"sv;
}

std::string FormatSceneJson(const sampling::SampledScene& sampled) {
  std::string out;
  out.reserve(256 + 512 * sampled.scene.objects.size());
  AppendSceneJson(sampled, out);
  return out;
}

void AppendSceneJson(const sampling::SampledScene& sampled, std::string& out) {
  AppendHeader(sampled, out);
  AppendParams(sampled.scene, out);
  out += ",\"objects\":[";
  for (size_t i = 0; i < sampled.scene.objects.size(); ++i) {
    if (i > 0) out += ',';
    AppendObject(sampled.scene.objects[i], out);
  }
  out += "]}";
}

std::vector<std::pair<std::string, double>> CalcSceneFeatures(const lang::Scene& scene) {
  std::vector<std::pair<std::string, double>> features;
  features.reserve(4 * scene.objects.size());
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const lang::SceneObject& o = scene.objects[i];
    const std::string name = o.DisplayName(static_cast<int>(i));
    const Eigen::Matrix3d R_WO = o.R_WO.toRotationMatrix();
    features.emplace_back(name + ".x", o.p_WO.x());
    features.emplace_back(name + ".y", o.p_WO.y());
    features.emplace_back(name + ".z", o.p_WO.z());
    // The heading of the object's x axis in the world's xy plane.
    features.emplace_back(name + ".yaw", std::atan2(R_WO(1, 0), R_WO(0, 0)));
  }
  return features;
}

}  // namespace prs::output
