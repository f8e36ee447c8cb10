#include "server/scenario/case_loader.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>

#include "server/scenario/case_units.h"
#include "server/scenario/case_validation.h"
#include "server/scenario/file_text.h"
#include "server/scenario/hyetograph.h"
#include "server/terrain/stl_solid.h"
#include "server/terrain/terrain_grid.h"

namespace cascade {

namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumValueDescriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::OneofDescriptor;
using google::protobuf::Reflection;
namespace pb = cascade::v1;

// Keys every case file states at its top level (h_over_dp may be left out for 1.3).
const char* const kRequiredTopLevelKeys[] = {"dimensions", "dp", "end_time"};

// One step of an override's key path: `bodies[0]` is {"bodies", 0}, `dp` is {"dp", -1}.
struct KeyStep {
  std::string name;
  int index = -1;
};

bool is_name_char(char c) {
  return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
}

// Splits "a.b[2].c" into its steps; an empty result means the text is not such a path.
std::vector<KeyStep> split_key(const std::string& key) {
  std::vector<KeyStep> steps;
  size_t i = 0;
  while (true) {
    KeyStep step;
    while (i < key.size() && is_name_char(key[i])) step.name += key[i++];
    if (step.name.empty()) return {};
    if (i < key.size() && key[i] == '[') {
      const size_t close = key.find(']', i);
      if (close == std::string::npos || close == i + 1 || close - i > 10) return {};
      for (size_t j = i + 1; j < close; ++j)
        if (!std::isdigit(static_cast<unsigned char>(key[j]))) return {};
      step.index = std::stoi(key.substr(i + 1, close - i - 1));
      i = close + 1;
    }
    steps.push_back(step);
    if (i == key.size()) return steps;
    if (key[i] != '.') return {};
    ++i;
  }
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::string join_path(const std::string& parent, const std::string& name) {
  return parent.empty() ? name : parent + "." + name;
}

std::string indexed(const std::string& key, size_t i) { return key + "[" + std::to_string(i) + "]"; }

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a mapping";
    default:
      return "nothing";
  }
}

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string field_names(const Descriptor* d) {
  std::string names;
  for (int i = 0; i < d->field_count(); ++i) names += (i ? ", " : "") + d->field(i)->name();
  return names;
}

// Maps a YAML tree onto a message by the message's descriptor, remembering where each key was so
// that later (semantic) errors can point to a line too.
class YamlMapper {
 public:
  YamlMapper(std::string file, const std::vector<CaseOverride>& overrides)
      : file_(std::move(file)), overrides_(overrides) {}

  void apply_overrides(YAML::Node& root) const {
    for (const CaseOverride& o : overrides_) apply_override(root, o);
  }

  void map_root(const YAML::Node& root, pb::ScenarioSpec* spec) {
    if (!root.IsMap()) {
      if (root.IsNull() || !root.IsDefined()) throw CaseError("(root)", "the case is empty", -1, -1, file_);
      fail("(root)", root.Mark(), "a case is a mapping of keys (dimensions: ..., dp: ..., ...), not " + describe(root));
    }
    map_message(root, spec, "");
    for (const char* key : kRequiredTopLevelKeys)
      if (!root[key].IsDefined())
        throw CaseError(key, "is missing: every case states dimensions, dp and end_time at its top level", -1, -1,
                        file_);
  }

  // The error for `key` found after mapping: at the key's line, or at its nearest enclosing key's.
  CaseError error_at(const std::string& key, const std::string& message) const {
    if (const CaseOverride* o = override_covering(key)) return from_override(key, message, *o);
    for (std::string k = key; !k.empty(); k = parent_key(k)) {
      const auto it = marks_.find(k);
      if (it != marks_.end()) return CaseError(key, message, it->second.line + 1, it->second.column + 1, file_);
    }
    return CaseError(key, message, -1, -1, file_);
  }

 private:
  [[noreturn]] void fail(const std::string& key, const YAML::Mark& mark, const std::string& message) const {
    if (const CaseOverride* o = override_covering(key)) throw from_override(key, message, *o);
    throw CaseError(key, message, mark.line + 1, mark.column + 1, file_);
  }

  CaseError from_override(const std::string& key, const std::string& message, const CaseOverride& o) const {
    return CaseError(key, message + " (from --set " + o.key + "=" + o.value + ")", -1, -1, file_);
  }

  // The last override whose key is `key` or encloses it.
  const CaseOverride* override_covering(const std::string& key) const {
    for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
      const std::string& k = it->key;
      if (key.compare(0, k.size(), k) == 0 && (key.size() == k.size() || key[k.size()] == '.' || key[k.size()] == '['))
        return &*it;
    }
    return nullptr;
  }

  static std::string parent_key(const std::string& key) {
    const auto cut = key.find_last_of(".[");
    return cut == std::string::npos ? std::string() : key.substr(0, cut);
  }

  [[noreturn]] void fail_override(const CaseOverride& o, const std::string& message) const {
    throw CaseError(o.key, message + " (from --set " + o.key + "=" + o.value + ")", -1, -1, file_);
  }

  void apply_override(YAML::Node& root, const CaseOverride& o) const {
    const std::vector<KeyStep> steps = split_key(o.key);
    if (steps.empty()) throw CaseError("--set", "'" + o.key + "' is not a key path like bodies[0].shape.box.max");
    check_override_against_schema(o, steps);
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      fail_override(o, "the value is not valid YAML: " + e.msg);
    }

    YAML::Node node = root;
    std::string path;
    for (size_t i = 0; i < steps.size(); ++i) {
      const KeyStep& step = steps[i];
      if (node.IsDefined() && !node.IsNull() && !node.IsMap())
        fail_override(o, "'" + path + "' is " + describe(node) + ", not a mapping with key '" + step.name + "'");
      path = join_path(path, step.name);
      YAML::Node child = node[step.name];  // created (as a mapping, later) when absent
      if (step.index >= 0) {
        if (!child.IsSequence()) fail_override(o, "'" + path + "' is not a list in the case");
        if (static_cast<size_t>(step.index) >= child.size())
          fail_override(o, "'" + path + "' has " + std::to_string(child.size()) + " elements, none at [" +
                               std::to_string(step.index) + "]");
        path = indexed(path, step.index);
        child.reset(child[step.index]);
      }
      node.reset(child);
    }
    node = value;
  }

  // Names the first step that is not a key of the schema, so that a typo in an override is an
  // error even where the case file has nothing at that place.
  void check_override_against_schema(const CaseOverride& o, const std::vector<KeyStep>& steps) const {
    const Descriptor* d = pb::ScenarioSpec::descriptor();
    std::string path;
    for (size_t i = 0; i < steps.size(); ++i) {
      const KeyStep& step = steps[i];
      if (d == nullptr) fail_override(o, "'" + path + "' is a value and has no key '" + step.name + "'");
      const FieldDescriptor* f = d->FindFieldByName(step.name);
      if (f == nullptr)
        fail_override(o, "unknown key '" + step.name + "'" + (path.empty() ? "" : " in " + path) +
                             " (known: " + field_names(d) + ")");
      path = join_path(path, step.name);
      if (step.index >= 0 && !f->is_repeated()) fail_override(o, "'" + path + "' is not a list and takes no index");
      if (step.index < 0 && f->is_repeated() && i + 1 < steps.size())
        fail_override(o, "'" + path + "' is a list: give an index, e.g. " + path + "[0]");
      if (step.index >= 0) path = indexed(path, static_cast<size_t>(step.index));
      d = f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE ? f->message_type() : nullptr;
    }
  }

  void map_message(const YAML::Node& node, Message* message, const std::string& path) {
    const Descriptor* d = message->GetDescriptor();
    if (!node.IsMap())
      fail(path, node.Mark(), "expected a mapping with keys among: " + field_names(d) + "; got " + describe(node));
    std::map<std::string, YAML::Mark> seen;
    std::map<const OneofDescriptor*, std::string> oneof_cases;
    for (const auto& entry : node) {  // a copy: yaml-cpp's iterators hand out temporaries
      const YAML::Node key_node = entry.first;
      const std::string name = key_node.IsScalar() ? key_node.Scalar() : std::string();
      const std::string key = join_path(path, name.empty() ? "?" : name);
      if (!key_node.IsScalar()) fail(key, key_node.Mark(), "a key must be a plain name, not " + describe(key_node));
      if (const auto previous = seen.find(name); previous != seen.end())
        fail(key, key_node.Mark(), "is given twice (first at line " + std::to_string(previous->second.line + 1) + ")");
      seen.emplace(name, key_node.Mark());
      const FieldDescriptor* field = d->FindFieldByName(name);
      if (field == nullptr) fail(key, key_node.Mark(), "unknown key (known here: " + field_names(d) + ")");
      marks_[key] = key_node.Mark();
      if (const OneofDescriptor* oneof = field->real_containing_oneof()) {
        const auto [other, added] = oneof_cases.emplace(oneof, name);
        if (!added)
          fail(key, key_node.Mark(),
               "cannot be given together with '" + other->second + "': " + (path.empty() ? "it" : path) +
                   " takes exactly one of " + oneof_names(oneof));
      }
      map_field(entry.second, key_node.Mark(), message, field, key);
    }
  }

  static std::string oneof_names(const OneofDescriptor* oneof) {
    std::string names;
    for (int i = 0; i < oneof->field_count(); ++i) names += (i ? ", " : "") + oneof->field(i)->name();
    return names;
  }

  void map_field(const YAML::Node& value, const YAML::Mark& key_mark, Message* message, const FieldDescriptor* field,
                 const std::string& key) {
    if (!field->is_repeated()) {
      if (field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE)
        map_message(value, message->GetReflection()->MutableMessage(message, field), key);
      else
        set_scalar(value, key_mark, message, field, key, false);
      return;
    }
    if (!value.IsSequence()) fail(key, key_mark, "expected a list, got " + describe(value));
    for (size_t i = 0; i < value.size(); ++i) {
      const YAML::Node element = value[i];
      const std::string element_key = indexed(key, i);
      marks_[element_key] = element.Mark();
      if (field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) {
        set_scalar(element, element.Mark(), message, field, element_key, true);
      } else {
        Message* item = message->GetReflection()->AddMessage(message, field);
        if (field->message_type() == pb::Point2::descriptor() && element.IsSequence())
          map_point2(element, static_cast<pb::Point2*>(item), element_key);
        else
          map_message(element, item, element_key);
      }
    }
  }

  // A vertex as an [x, z] pair.
  void map_point2(const YAML::Node& node, pb::Point2* point, const std::string& key) const {
    if (node.size() != 2)
      fail(key, node.Mark(), "a vertex is an [x, z] pair, not " + std::to_string(node.size()) + " numbers");
    const Descriptor* d = pb::Point2::descriptor();
    point->set_x(to_double(node[0], node[0].Mark(), indexed(key, 0), si_unit_of(d->FindFieldByName("x"))));
    point->set_z(to_double(node[1], node[1].Mark(), indexed(key, 1), si_unit_of(d->FindFieldByName("z"))));
  }

  // A number, or "<number> <unit>" for a field whose schema names its SI unit `si_unit` (empty:
  // a plain number), converted to that unit.
  double to_double(const YAML::Node& node, const YAML::Mark& mark, const std::string& key,
                   const std::string& si_unit) const {
    double v = 0;
    if (plain_scalar(node) && YAML::convert<double>::decode(node, v)) {
      if (!std::isfinite(v)) fail(key, mark, "expected a finite number, got " + describe(node));
      return v;
    }
    const std::optional<NumberWithUnit> given = node.IsScalar() ? split_number_with_unit(node.Scalar()) : std::nullopt;
    if (!given)
      fail(key, mark,
           "expected a number, got " + describe(node) +
               (si_unit.empty() || !node.IsScalar()
                    ? std::string()
                    : " (or a number and a unit of " + dimension_name(si_unit) + ": " + unit_names(si_unit) + ")"));
    if (si_unit.empty()) fail(key, mark, "takes a plain number without a unit, got " + describe(node));
    if (const std::string problem = unit_problem(given->unit, si_unit); !problem.empty()) fail(key, mark, problem);
    v = find_case_unit(given->unit)->to_si(given->number);
    if (!std::isfinite(v)) fail(key, mark, "expected a finite number, got " + describe(node));
    return v;
  }

  // Numbers and booleans are plain scalars: a quoted "0.02" is text.
  static bool plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }

  // An integer field's value: a plain whole number within [lo, hi], else an error that says `what`.
  long long whole_number(const YAML::Node& node, const YAML::Mark& mark, const std::string& key, long long lo,
                         long long hi, const std::string& what) const {
    long long v = 0;
    if (!plain_scalar(node) || !YAML::convert<long long>::decode(node, v) || v < lo || v > hi)
      fail(key, mark, "expected " + what + ", got " + describe(node));
    return v;
  }

  void set_scalar(const YAML::Node& node, const YAML::Mark& key_mark, Message* message, const FieldDescriptor* field,
                  const std::string& key, bool add) const {
    const Reflection* r = message->GetReflection();
    // Errors point at the value when it has its own place (a list element), else at its key.
    const YAML::Mark& mark = add ? node.Mark() : key_mark;
    if (node.IsNull() || !node.IsDefined()) fail(key, mark, "has no value");
    switch (field->cpp_type()) {
      case FieldDescriptor::CPPTYPE_DOUBLE: {
        const double v = to_double(node, mark, key, si_unit_of(field));
        add ? r->AddDouble(message, field, v) : r->SetDouble(message, field, v);
        return;
      }
      case FieldDescriptor::CPPTYPE_INT32: {
        const auto v = static_cast<int32_t>(whole_number(node, mark, key, std::numeric_limits<int32_t>::min(),
                                                         std::numeric_limits<int32_t>::max(), "a whole number"));
        add ? r->AddInt32(message, field, v) : r->SetInt32(message, field, v);
        return;
      }
      case FieldDescriptor::CPPTYPE_UINT32: {  // a mesh's vertex indices
        const auto v = static_cast<uint32_t>(
            whole_number(node, mark, key, 0, std::numeric_limits<uint32_t>::max(), "a whole number >= 0"));
        add ? r->AddUInt32(message, field, v) : r->SetUInt32(message, field, v);
        return;
      }
      case FieldDescriptor::CPPTYPE_BOOL: {
        bool v = false;
        if (!plain_scalar(node) || !YAML::convert<bool>::decode(node, v))
          fail(key, mark, "expected true or false, got " + describe(node));
        add ? r->AddBool(message, field, v) : r->SetBool(message, field, v);
        return;
      }
      case FieldDescriptor::CPPTYPE_STRING: {
        if (!node.IsScalar()) fail(key, mark, "expected a text value, got " + describe(node));
        add ? r->AddString(message, field, node.Scalar()) : r->SetString(message, field, node.Scalar());
        return;
      }
      case FieldDescriptor::CPPTYPE_ENUM: {
        const EnumValueDescriptor* value = enum_value(node, field);
        if (value == nullptr) fail(key, mark, "expected one of " + enum_names(field) + ", got " + describe(node));
        add ? r->AddEnum(message, field, value) : r->SetEnum(message, field, value);
        return;
      }
      default:
        throw std::logic_error("case loader: no YAML mapping for the type of field " + field->full_name());
    }
  }

  // Enum values are written as their names in lowercase; the UNSPECIFIED value (0) is not one.
  static const EnumValueDescriptor* enum_value(const YAML::Node& node, const FieldDescriptor* field) {
    if (!node.IsScalar()) return nullptr;
    const auto* e = field->enum_type();
    for (int i = 0; i < e->value_count(); ++i)
      if (e->value(i)->number() != 0 && lowercase(e->value(i)->name()) == node.Scalar()) return e->value(i);
    return nullptr;
  }

  static std::string enum_names(const FieldDescriptor* field) {
    std::string names;
    const auto* e = field->enum_type();
    for (int i = 0; i < e->value_count(); ++i)
      if (e->value(i)->number() != 0) names += (names.empty() ? "" : ", ") + lowercase(e->value(i)->name());
    return names;
  }

  std::string file_;
  const std::vector<CaseOverride>& overrides_;
  std::map<std::string, YAML::Mark> marks_;
};

// The unit of a hyetograph column: `name`, or `si` when it is empty.
const CaseUnit& column_unit(const std::string& name, const std::string& si, const std::string& key,
                            const YamlMapper& mapper) {
  const std::string written = name.empty() ? si : name;
  if (const std::string problem = unit_problem(written, si); !problem.empty()) throw mapper.error_at(key, problem);
  return *find_case_unit(written);
}

// Replaces the case's hyetograph with the `rainfall` series of its CSV file (read relative to the
// case file's folder) and records the file in `rainfall_file`. Errors in the CSV name the key
// `hydraulics.hyetograph.file` at its line in the case, and the CSV file and line in the message.
void expand_hyetograph(pb::HydraulicBoundary& hydraulics, const std::filesystem::path& case_directory,
                       const YamlMapper& mapper) {
  const std::string key = "hydraulics.hyetograph";
  const pb::Hyetograph& hyetograph = hydraulics.hyetograph();
  if (hydraulics.rainfall_intensity() != 0 || hydraulics.rainfall_size() > 0)
    throw mapper.error_at(key,
                          "cannot be given together with rainfall_intensity or rainfall: the rain is a "
                          "constant intensity, a series or a hyetograph");
  if (!hydraulics.rainfall_file().empty())
    throw mapper.error_at("hydraulics.rainfall_file", "is set by the loader from hyetograph.file: leave it out");
  const CaseUnit& time_unit = column_unit(hyetograph.time_unit(), "s", key + ".time_unit", mapper);
  const CaseUnit& intensity_unit = column_unit(hyetograph.intensity_unit(), "m/s", key + ".intensity_unit", mapper);
  if (hyetograph.file().empty()) throw mapper.error_at(key + ".file", "is missing: the CSV file of time and intensity");
  const std::string file = (case_directory / hyetograph.file()).lexically_normal().string();
  const std::optional<std::string> text = file_text(file);
  if (!text) throw mapper.error_at(key + ".file", "cannot read the hyetograph " + file);
  try {
    for (pb::RainfallPoint& point : read_hyetograph(*text, time_unit, intensity_unit))
      *hydraulics.add_rainfall() = std::move(point);
  } catch (const HyetographError& e) {
    throw mapper.error_at(key + ".file",
                          file + (e.line() > 0 ? ":" + std::to_string(e.line()) : std::string()) + ": " + e.what());
  }
  hydraulics.set_rainfall_file(file);
  hydraulics.clear_hyetograph();
}

// The offset of the first byte that is not part of a well-formed UTF-8 sequence (no overlong
// forms, no surrogates, nothing above U+10FFFF: what protobuf accepts in a string), or npos.
std::size_t first_non_utf8_byte(const std::string& text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = byte(i);
    const int extra = c < 0x80 ? 0 : c >= 0xC2 && c <= 0xDF ? 1 : c >= 0xE0 && c <= 0xEF ? 2 : c >= 0xF0 && c <= 0xF4 ? 3 : -1;
    if (extra < 0 || i + extra >= text.size() + (extra == 0 ? 1 : 0)) return i;
    for (int k = 1; k <= extra; ++k)
      if ((byte(i + k) & 0xC0) != 0x80) return i;
    if (extra >= 2) {
      const unsigned char next = byte(i + 1);
      if ((c == 0xE0 && next < 0xA0) || (c == 0xED && next >= 0xA0) || (c == 0xF0 && next < 0x90) ||
          (c == 0xF4 && next >= 0x90))
        return i;
    }
    i += std::size_t(extra) + 1;
  }
  return std::string::npos;
}

// A case is UTF-8 text (YAML's encoding, and protobuf's for the strings a case fills): a Latin-1
// comment was accepted by `cascade run` and made CreateSimulation fail with an empty UNIMPLEMENTED
// (issue 14). The error names the line and column of the first foreign byte.
void require_utf8(const std::string& text, const std::string& file_name) {
  const std::size_t at = first_non_utf8_byte(text);
  if (at == std::string::npos) return;
  const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
  const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
  const int column = 1 + int(at - (line_start == std::string::npos || at == 0 ? 0 : line_start + 1));
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(text[at])));
  throw CaseError("(encoding)", std::string("byte ") + hex + " is not UTF-8: save the case file as UTF-8 (Latin-1 "
                  "accents, for one, are not)", line, column, file_name);
}

// The first line (1-based) that opens a quoted string and does not close it, or 0. YAML lets a
// quoted scalar run on over lines, so a forgotten quote swallowed the keys after it and yaml-cpp
// reported the consequence far below ("key 'dimensions' is missing", or "end of map not found" at
// the next quote), not the cause (issue 14). A case's strings are one line each, so such a line
// is refused where it is.
int first_unclosed_quote_line(const std::string& text) {
  int line = 1;
  char open = 0;  // the quote character of the string being read, 0 outside a string
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      if (open) return line;
      ++line, comment = false;
      continue;
    }
    if (comment) continue;
    if (open == '"' && c == '\\') {
      ++i;  // an escape inside double quotes
    } else if (open == '\'' && c == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
      ++i;  // '' inside single quotes
    } else if (open && c == open) {
      open = 0;
    } else if (!open && (c == '"' || c == '\'') && (i == 0 || std::strchr(" \t\n:[{,-", text[i - 1]))) {
      open = c;
    } else if (!open && c == '#' && (i == 0 || std::strchr(" \t\n", text[i - 1]))) {
      comment = true;
    }
  }
  return open ? line : 0;
}

// load_case_text and load_case_file: a case file has a folder, from which its hyetograph is read;
// a case given as text has none, and a hyetograph in it is left for check_spec to refuse.
pb::ScenarioSpec load_case(const std::string& yaml_text, const std::vector<CaseOverride>& overrides,
                           const std::string& file_name, const std::optional<std::filesystem::path>& case_directory) {
  require_utf8(yaml_text, file_name);
  if (const int quote = first_unclosed_quote_line(yaml_text); quote > 0)
    throw CaseError("(yaml)", "a quote opened on this line is not closed on it (a case's strings are one line each)",
                    quote, -1, file_name);
  YamlMapper mapper(file_name, overrides);
  pb::ScenarioSpec spec;
  try {
    YAML::Node root = YAML::Load(yaml_text);
    mapper.apply_overrides(root);
    mapper.map_root(root, &spec);
  } catch (const YAML::Exception& e) {
    // Syntax errors, and anything else yaml-cpp finds wrong with the text.
    throw CaseError("(yaml)", e.msg, e.mark.is_null() ? -1 : e.mark.line + 1, e.mark.column + 1, file_name);
  }
  if (case_directory && spec.hydraulics().has_hyetograph())
    expand_hyetograph(*spec.mutable_hydraulics(), *case_directory, mapper);
  if (case_directory && names_terrain_rasters(spec.terrain()))
    expand_terrain(*spec.mutable_terrain(), spec.dimensions(), spec.dp(), *case_directory,
                   [&](const std::string& key, const std::string& message) { throw mapper.error_at(key, message); });
  if (case_directory && names_stl_files(spec))  // after the terrain, whose origin map coordinates need
    expand_stl_meshes(spec, *case_directory,
                      [&](const std::string& key, const std::string& message) { throw mapper.error_at(key, message); });
  check_spec(spec, [&](const std::string& key, const std::string& message) { throw mapper.error_at(key, message); });
  apply_defaults(spec);
  return spec;
}

}  // namespace

CaseOverride parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) throw CaseError("--set", "'" + text + "' is not of the form path.to.key=value");
  CaseOverride o{trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
  if (split_key(o.key).empty())
    throw CaseError("--set", "'" + o.key + "' is not a key path like dp or bodies[0].shape.box.max");
  if (o.value.empty()) throw CaseError("--set", "'" + text + "' gives no value after '='");
  try {
    YAML::Load(o.value);
  } catch (const YAML::Exception& e) {
    throw CaseError("--set", "the value of '" + text + "' is not valid YAML: " + e.msg);
  }
  return o;
}

pb::ScenarioSpec load_case_text(const std::string& yaml_text, const std::vector<CaseOverride>& overrides,
                                const std::string& file_name) {
  return load_case(yaml_text, overrides, file_name, std::nullopt);
}

pb::ScenarioSpec load_case_file(const std::string& path, const std::vector<CaseOverride>& overrides) {
  const std::optional<std::string> text = file_text(path);
  if (!text) throw CaseError("(file)", "cannot open the case file", -1, -1, path);
  pb::ScenarioSpec spec = load_case(*text, overrides, path, std::filesystem::path(path).parent_path());
  if (spec.name().empty()) {
    const auto slash = path.find_last_of('/');
    std::string stem = path.substr(slash == std::string::npos ? 0 : slash + 1);
    spec.set_name(stem.substr(0, stem.find_last_of('.')));
  }
  return spec;
}

}  // namespace cascade
