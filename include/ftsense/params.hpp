#pragma once
// Plugin parameters, described once.
//
// A plugin's `Params` is a plain struct whose member initialisers are the defaults, plus a static
// `describe` that names every field once with its type, description, unit, bounds or choices:
//
//   struct Params {
//     double cutoff_hz = 5.0;
//     static void describe(ftsense::ParamSchema<Params>& s) {
//       s.add("cutoff_hz", &Params::cutoff_hz, "low-pass cut-off frequency").unit("Hz").greater_than(0);
//     }
//   };
//
// From that one description ftsense loads JSON strictly (unknown keys, missing required keys,
// wrong types, out-of-bounds values and unknown choices are all errors, collected together with
// their JSON Pointer path), saves JSON (round trip), and generates docs/config_reference.md.
//
// Bounds say what the code can compute with; a *plausible range* says what a real robot needs:
//
//       s.add("mass_kg", ...).unit("kg").greater_than(0).plausible(0.5, 1000, "robot mass: ...");
//
// A value outside the bounds is an error; inside them but outside the plausible range it is a
// warning with its JSON Pointer (a unit slip such as grams for kilograms, a typo such as 1e-300),
// which `ftsense check` and `ftsense run` print and which does not stop the pipeline.
//
// An optional member `void validate(Diagnostics&, std::string_view path) const` adds
// cross-field rules; it runs only when every field loaded.

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "ftsense/diagnostics.hpp"

namespace ftsense {

using Json = nlohmann::json;

enum class ParamKind { number, integer, boolean, text, choice, number_list, point_list, text_list };
[[nodiscard]] std::string_view to_string(ParamKind kind);

struct ParamBound {
  double value = 0.0;
  bool inclusive = true;
};

// Values a real robot plausibly needs, [low, high] in the parameter's unit, and why.
struct PlausibleRange {
  double low = 0.0;
  double high = 0.0;
  std::string reason;  // what the range spans, e.g. "robot mass: 1 kg toys to 300 kg machines"

  // "0.5 .. 1000 kg (robot mass: ...)" (the unit is left out when empty).
  [[nodiscard]] std::string text(std::string_view unit) const;
};

// What a parameter is, as users read it (type erased: the same for every Params struct).
struct ParamInfo {
  std::string key;
  std::string description;
  std::string unit;  // SI unit symbol; empty when dimensionless
  ParamKind kind = ParamKind::number;
  bool required = false;
  std::optional<ParamBound> lower;
  std::optional<ParamBound> upper;
  std::size_t min_count = 0;  // lists only
  std::size_t max_count = std::numeric_limits<std::size_t>::max();
  std::vector<std::string> choices;  // choice only
  Json default_value;                // null when required
  std::optional<PlausibleRange> plausible;  // numbers only (each entry of a list)

  // The value rule in words: "> 0", ">= 0 and <= 1", "one of: planned, measured", ...
  [[nodiscard]] std::string rule() const;
  // "(description, unit)" as used at the end of error messages.
  [[nodiscard]] std::string what() const;
};

namespace detail {
// Checks a scalar against the bounds of `info`; reports "path = value violates rule (what)".
void check_number(const ParamInfo& info, double value, const Json& raw, const std::string& path,
                  Diagnostics& diag);
void report_type(const ParamInfo& info, const Json& raw, std::string_view expected,
                 const std::string& path, Diagnostics& diag);
bool read_number(const ParamInfo& info, const Json& raw, const std::string& path, Diagnostics& diag,
                 double& out);
bool read_integer(const ParamInfo& info, const Json& raw, const std::string& path, Diagnostics& diag,
                  long long& out);
bool check_count(const ParamInfo& info, const Json& raw, const std::string& path, Diagnostics& diag);
std::string abbreviated_dump(const Json& value);
}  // namespace detail

// Warns "path = value is outside the plausible range ...; check the unit or the value" when a
// (valid) value lies outside `range`. Used for plugin parameters and the pipeline document alike.
void check_plausible(const PlausibleRange& range, std::string_view unit, double value, const Json& raw,
                     const std::string& path, Diagnostics& diag);

template <class P>
class ParamSchema {
 public:
  struct Field {
    ParamInfo info;
    std::function<void(const Json&, P&, const std::string&, Diagnostics&)> load;
    std::function<Json(const P&)> save;
  };

  // Chainable setters for the field just added.
  class FieldBuilder {
   public:
    explicit FieldBuilder(Field& field) : field_(&field) {}
    FieldBuilder& unit(std::string u) { field_->info.unit = std::move(u); return *this; }
    FieldBuilder& required() {
      field_->info.required = true;
      field_->info.default_value = nullptr;
      return *this;
    }
    FieldBuilder& greater_than(double v) { field_->info.lower = ParamBound{v, false}; return *this; }
    FieldBuilder& at_least(double v) { field_->info.lower = ParamBound{v, true}; return *this; }
    FieldBuilder& less_than(double v) { field_->info.upper = ParamBound{v, false}; return *this; }
    FieldBuilder& at_most(double v) { field_->info.upper = ParamBound{v, true}; return *this; }
    FieldBuilder& count_at_least(std::size_t n) { field_->info.min_count = n; return *this; }
    FieldBuilder& count_at_most(std::size_t n) { field_->info.max_count = n; return *this; }
    // Call after the bounds: the plausible range must lie within them.
    FieldBuilder& plausible(double low, double high, std::string reason) {
      return plausible(PlausibleRange{low, high, std::move(reason)});
    }
    FieldBuilder& plausible(PlausibleRange range) {
      const ParamInfo& info = field_->info;
      const double low = range.low, high = range.high;
      FTSENSE_DEMAND(info.kind == ParamKind::number || info.kind == ParamKind::integer ||
                         info.kind == ParamKind::number_list || info.kind == ParamKind::point_list,
                     "a plausible range is for numbers: " + info.key);
      FTSENSE_DEMAND(low < high, "plausible range of " + info.key + " is empty");
      FTSENSE_DEMAND(!info.lower || low >= info.lower->value, "plausible range of " + info.key + " below its bound");
      FTSENSE_DEMAND(!info.upper || high <= info.upper->value, "plausible range of " + info.key + " above its bound");
      field_->info.plausible = std::move(range);
      return *this;
    }

   private:
    Field* field_;
  };

  // Adds a field of type double, int, bool, std::string, std::vector<double>,
  // std::vector<std::string> or std::vector<std::array<double, 2>> (points). Enums use add_choice.
  template <class T>
  FieldBuilder add(std::string key, T P::*member, std::string description) {
    Field& f = push(std::move(key), std::move(description));
    f.info.kind = kind_of<T>();
    // The loader looks its info up by index at load time: FieldBuilder refines it after add().
    const std::size_t index = fields_.size() - 1;
    f.load = [this_schema = this, index, member](const Json& raw, P& p, const std::string& path,
                                                 Diagnostics& diag) {
      load_value(this_schema->fields_[index].info, raw, p.*member, path, diag);
    };
    f.save = [member](const P& p) { return Json(p.*member); };
    return FieldBuilder(f);
  }

  // Adds an enum field carried in JSON as one of the given strings.
  template <class E>
  FieldBuilder add_choice(std::string key, E P::*member, std::string description,
                          std::vector<std::pair<std::string, E>> choices) {
    static_assert(std::is_enum_v<E>, "add_choice is for enum fields");
    Field& f = push(std::move(key), std::move(description));
    f.info.kind = ParamKind::choice;
    for (const auto& c : choices) f.info.choices.push_back(c.first);
    const std::size_t index = fields_.size() - 1;
    f.load = [this_schema = this, index, member, choices](const Json& raw, P& p,
                                                          const std::string& path,
                                                          Diagnostics& diag) {
      const ParamInfo& info = this_schema->fields_[index].info;
      if (!raw.is_string()) return detail::report_type(info, raw, "string", path, diag);
      const auto& s = raw.template get_ref<const std::string&>();
      for (const auto& [name, value] : choices) {
        if (name == s) {
          p.*member = value;
          return;
        }
      }
      diag.error(path, " = " + raw.dump() + " violates " + info.rule() + " " + info.what() + "; " +
                           suggest(s, info.choices));
    };
    f.save = [member, choices](const P& p) {
      for (const auto& [name, value] : choices) {
        if (value == p.*member) return Json(name);
      }
      return Json(nullptr);
    };
    return FieldBuilder(f);
  }

  [[nodiscard]] const std::vector<Field>& fields() const { return fields_; }

  ParamSchema() = default;
  ParamSchema(const ParamSchema&) = delete;  // the loaders point back into this object
  ParamSchema& operator=(const ParamSchema&) = delete;

 private:
  Field& push(std::string key, std::string description) {
    for (const auto& f : fields_) {
      FTSENSE_DEMAND(f.info.key != key, "parameter described twice: " + key);
    }
    fields_.emplace_back();
    fields_.back().info.key = std::move(key);
    fields_.back().info.description = std::move(description);
    return fields_.back();
  }

  template <class T>
  static constexpr ParamKind kind_of() {
    if constexpr (std::is_same_v<T, double>) return ParamKind::number;
    else if constexpr (std::is_same_v<T, int>) return ParamKind::integer;
    else if constexpr (std::is_same_v<T, bool>) return ParamKind::boolean;
    else if constexpr (std::is_same_v<T, std::string>) return ParamKind::text;
    else if constexpr (std::is_same_v<T, std::vector<double>>) return ParamKind::number_list;
    else if constexpr (std::is_same_v<T, std::vector<std::array<double, 2>>>)
      return ParamKind::point_list;
    else if constexpr (std::is_same_v<T, std::vector<std::string>>) return ParamKind::text_list;
    else static_assert(sizeof(T) == 0,
                       "ftsense parameter type must be double, int, bool, std::string, "
                       "std::vector<double>, std::vector<std::string> or "
                       "std::vector<std::array<double, 2>>; "
                       "use add_choice for enums");
  }

  static void load_value(const ParamInfo& info, const Json& raw, double& out,
                         const std::string& path, Diagnostics& diag) {
    double v = 0;
    if (detail::read_number(info, raw, path, diag, v)) out = v;
  }
  static void load_value(const ParamInfo& info, const Json& raw, int& out, const std::string& path,
                         Diagnostics& diag) {
    long long v = 0;
    if (!detail::read_integer(info, raw, path, diag, v)) return;
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
      diag.error(path, " = " + raw.dump() + " violates the range of a 32-bit integer " + info.what());
      return;
    }
    out = static_cast<int>(v);
  }
  static void load_value(const ParamInfo& info, const Json& raw, bool& out,
                         const std::string& path, Diagnostics& diag) {
    if (!raw.is_boolean()) return detail::report_type(info, raw, "boolean", path, diag);
    out = raw.get<bool>();
  }
  static void load_value(const ParamInfo& info, const Json& raw, std::string& out,
                         const std::string& path, Diagnostics& diag) {
    if (!raw.is_string()) return detail::report_type(info, raw, "string", path, diag);
    out = raw.get<std::string>();
  }
  static void load_value(const ParamInfo& info, const Json& raw, std::vector<double>& out,
                         const std::string& path, Diagnostics& diag) {
    if (!raw.is_array()) return detail::report_type(info, raw, "array of numbers", path, diag);
    bool ok = detail::check_count(info, raw, path, diag);
    std::vector<double> values(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
      ok = detail::read_number(info, raw[i], json_pointer_append(path, i), diag, values[i]) && ok;
    }
    if (ok) out = std::move(values);
  }
  static void load_value(const ParamInfo& info, const Json& raw, std::vector<std::string>& out,
                         const std::string& path, Diagnostics& diag) {
    if (!raw.is_array()) return detail::report_type(info, raw, "array of strings", path, diag);
    bool ok = detail::check_count(info, raw, path, diag);
    std::vector<std::string> values;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (!raw[i].is_string()) {
        detail::report_type(info, raw[i], "string", json_pointer_append(path, i), diag);
        ok = false;
        continue;
      }
      values.push_back(raw[i].template get<std::string>());
    }
    if (ok) out = std::move(values);
  }
  static void load_value(const ParamInfo& info, const Json& raw,
                         std::vector<std::array<double, 2>>& out, const std::string& path,
                         Diagnostics& diag) {
    if (!raw.is_array()) return detail::report_type(info, raw, "array of [x, y] points", path, diag);
    bool ok = detail::check_count(info, raw, path, diag);
    std::vector<std::array<double, 2>> values(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
      const std::string item_path = json_pointer_append(path, i);
      const Json& item = raw[i];
      if (!item.is_array() || item.size() != 2) {
        detail::report_type(info, item, "[x, y] point (array of 2 numbers)", item_path, diag);
        ok = false;
        continue;
      }
      for (std::size_t k = 0; k < 2; ++k) {
        ok = detail::read_number(info, item[k], json_pointer_append(item_path, k), diag,
                                 values[i][k]) &&
             ok;
      }
    }
    if (ok) out = std::move(values);
  }

  std::vector<Field> fields_;
};

// The one schema of a Params type, built on first use from Params::describe.
template <class P>
const ParamSchema<P>& param_schema() {
  static const ParamSchema<P>& schema = *[] {
    auto* s = new ParamSchema<P>();  // never freed: lives as long as the program, like a registry
    P::describe(*s);
    return s;
  }();
  return schema;
}

template <class P>
std::vector<ParamInfo> param_infos() {
  std::vector<ParamInfo> out;
  const P defaults{};
  for (const auto& f : param_schema<P>().fields()) {
    out.push_back(f.info);
    if (!f.info.required) out.back().default_value = f.save(defaults);
  }
  return out;
}

template <class P>
concept HasParamValidation = requires(const P& p, Diagnostics& d, std::string_view path) {
  { p.validate(d, path) } -> std::same_as<void>;
};

// Loads `raw` (a JSON object) into a default-constructed P. Problems go to `diag`, paths under
// `path`; `owner` names what the parameters belong to in messages (a plugin name).
template <class P>
P load_params(const Json& raw, std::string_view path, std::string_view owner, Diagnostics& diag) {
  P params{};
  const std::string base(path);
  if (!raw.is_object()) {
    diag.error(base, " = " + detail::abbreviated_dump(raw) + " has type " + raw.type_name() +
                         ", expected object (the parameters of " + std::string(owner) + ")");
    return params;
  }
  const auto& schema = param_schema<P>();
  std::vector<std::string> known;
  for (const auto& f : schema.fields()) known.push_back(f.info.key);
  const std::size_t errors_before = diag.errors().size();
  for (const auto& [key, value] : raw.items()) {
    bool found = false;
    for (const auto& f : schema.fields()) found = found || f.info.key == key;
    if (!found) {
      diag.error(json_pointer_append(base, key),
                 "unknown parameter of " + std::string(owner) + "; " + suggest(key, known));
    }
  }
  for (const auto& f : schema.fields()) {
    const std::string field_path = json_pointer_append(base, f.info.key);
    const auto it = raw.find(f.info.key);
    if (it == raw.end()) {
      if (f.info.required) {
        diag.error(field_path, "missing required parameter " + f.info.what() +
                                   "; add it to the parameters of " + std::string(owner));
      }
      continue;
    }
    f.load(*it, params, field_path, diag);
  }
  if constexpr (HasParamValidation<P>) {
    if (diag.errors().size() == errors_before) params.validate(diag, base);
  }
  return params;
}

template <class P>
Json save_params(const P& params) {
  Json out = Json::object();
  for (const auto& f : param_schema<P>().fields()) out[f.info.key] = f.save(params);
  return out;
}

}  // namespace ftsense
