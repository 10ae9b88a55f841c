#include "io/units.h"

#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

namespace beamid::io {

namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g (CGPM 1901)
constexpr double kInch = 0.0254;              // m per inch (exact since 1959)
constexpr double kFoot = 0.3048;              // m per foot (exact since 1959)

std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\"'");
  if (first == std::string_view::npos) return "";
  return std::string(text.substr(first, text.find_last_not_of(" \t\"'") - first + 1));
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// The unit a label spells, in beamid's spelling, or "" (case-insensitive). A bare "v", "n" or "in" is volts, newtons
// or inches only in a label ("(V)", an LVM unit): as a name's suffix it is as likely a velocity ("tip_v"), an index
// ("x_n") or an input ("force_in").
std::string known_unit(std::string u, bool label) {
  u = lower(trimmed(u));
  // The micro sign (UTF-8 C2 B5) and Greek mu (CE BC) as u; the superscript two (C2 B2) as ^2.
  // Negative exponents as written in SI style ("mm s-1", "mm.s-2", "m\xc2\xb7s-1") and "per" as '/' (the fifth pass's
  // R008-R017), before the spaces go.
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\xc2\xb5", "u"},
                                 {"\xce\xbc", "u"},
                                 {"\xe2\x81\xbb\xc2\xb2", "-2"},
                                 {"\xe2\x81\xbb\xc2\xb9", "-1"},
                                 {"\xc2\xb2", "^2"},
                                 {"\xe2\x81\xbb", "-"},  // superscript minus and one: "mm\xc2\xb7s\xe2\x81\xbb\xc2\xb9"
                                 {"\xc2\xb9", "1"},      // (the seventh pass's U042)
                                 {"**", "^"},
                                 {" per ", "/"},
                                 {"\xc2\xb7", " "},
                                 {".s-", " s-"},
                                 {" s^-1", "/s"},
                                 {" s-1", "/s"},
                                 {" s^-2", "/s^2"},
                                 {" s-2", "/s^2"},
                                 {"/sec", "/s"},
                                 {" ", ""}}) {
    for (auto at = u.find(from); at != std::string::npos; at = u.find(from, at + to.size()))
      u.replace(at, from.size(), to);
  }
  static constexpr std::pair<const char*, const char*> spellings[] = {
      {"kmh", "km/h"},      {"kph", "km/h"},
      {"micrometre", "um"}, {"micrometres", "um"},
      {"micrometer", "um"}, {"micrometers", "um"},
      {"centimetre", "cm"}, {"centimetres", "cm"},
      {"centimeter", "cm"}, {"centimeters", "cm"},
      {"nanometre", "nm"},  {"nanometres", "nm"},
      {"nanometer", "nm"},  {"nanometers", "nm"},
      {"kilometre", "km"},  {"kilometres", "km"},
      {"yard", "yd"},       {"yards", "yd"},
      {"mils", "mil"},      {"thou", "mil"},
      {"gee", "g"},         {"milli-g", "mg"},
      {"in.", "in"},        {"cm/s", "cm/s"},
      {"meter", "m"},       {"meters", "m"},
      {"metre", "m"},       {"metres", "m"},
      {"micron", "um"},     {"microns", "um"},
      {"millimeter", "mm"}, {"millimeters", "mm"},
      {"millimetre", "mm"}, {"millimetres", "mm"},
      {"mm/sec", "mm/s"},   {"km", "km"},
      {"yd", "yd"},         {"mil", "mil"},
      {"mph", "mph"},       {"pm", "pm"},
      {"inch", "in"},       {"inches", "in"},
      {"feet", "ft"},       {"foot", "ft"},
      {"gal", "Gal"},       {"g", "g"},
      {"g's", "g"},         {"gs", "g"},
      {"gn", "g"},          {"g_n", "g"},
      {"mg", "mg"},         {"m", "m"},
      {"cm", "cm"},         {"mm", "mm"},
      {"um", "um"},         {"nm", "nm"},
      {"in", "in"},         {"ft", "ft"},
      {"m/s", "m/s"},       {"ms^-1", "m/s"},
      {"mm/s", "mm/s"},     {"in/s", "in/s"},
      {"ips", "in/s"},      {"ft/s", "ft/s"},
      {"km/h", "km/h"},     {"m/s^2", "m/s^2"},
      {"m/s2", "m/s^2"},    {"ms^-2", "m/s^2"},
      {"m/s/s", "m/s^2"},   {"mm/s^2", "mm/s^2"},
      {"mm/s2", "mm/s^2"},  {"in/s^2", "in/s^2"},
      {"in/s2", "in/s^2"},  {"ft/s^2", "ft/s^2"},
      {"ft/s2", "ft/s^2"},  {"v", "V"},
      {"volt", "V"},        {"volts", "V"},
      {"mv", "mV"},         {"n", "N"},
      {"newton", "N"},      {"newtons", "N"},
      {"lbf", "lbf"},       {"pa", "Pa"},
      {"kn", "kN"},         {"um/s", "um/s"},
  };
  if (!label && (u == "v" || u == "n" || u == "in")) return "";
  for (const auto& [spelling, unit] : spellings)
    if (u == spelling) return unit;
  return "";
}

// Whether a label is a unit, though not one beamid converts: a time unit ("ms" in a value column was read as m/s), or
// a motion unit with a capital M, which is mega, not milli ("Mm" was read as mm, 1e9 times off). All capitals ("MM",
// "MM/S") are read as shouted lower case.
bool is_unconverted_unit(const std::string& label, bool in_brackets) {
  const std::string t = trimmed(label);
  const bool has_lower = std::any_of(t.begin(), t.end(), [](unsigned char c) { return std::islower(c) != 0; });
  if (t.size() > 1 && t[0] == 'M' && has_lower) {
    const std::string base = known_unit(t.substr(1), true);
    if (base == "m" || base == "m/s" || base == "m/s^2" || base == "g" || base == "V") return true;
  }
  const std::string l = lower(t);
  if (l == "ms" || l == "us" || l == "msec" || l == "usec") return true;
  if (!in_brackets) return false;  // as a suffix, "tip_s" or "x_h" is as likely a name
  for (const char* unit : {"s", "sec", "min", "h", "hz", "khz", "rad", "deg", "degc", "degf", "k", "kg", "g/cm3", "lb",
                           "psi", "kpa", "mpa", "bar", "a", "ma", "w", "j", "nm/rad", "rpm", "%", "db", "ohm", "ue",
                           "\xc2\xb5\xce\xb5", "strain", "ustrain", "microstrain",
                           // Prefixed volts, newtons and pascals beside the known V, mV, N, kN, Pa: a sensor's raw
                           // signal in another prefix, read as SI motion (the fourteenth pass's P4).
                           "uv", "nv", "kv", "mn", "un", "dn", "gpa", "mile", "miles", "furlong", "fathom", "counts",
                           "count", "cnt", "adc", "lsb", "digits", "dm", "gee", "knot", "knots", "kt", "g0", "gravity"})
    if (l == unit) return true;
  // Any SI prefix on volts, newtons, pascals, amperes, watts, bars or g, other than the ones beamid knows (V, mV, N,
  // kN, Pa, g, mg), is a unit beamid does not know, never a remark: a list of prefixed forms left holes ((pV), (daN),
  // (hPa), (mbar), (ug) were read as metres), and upper case collided with known units ((MV) as mV, (GN) as g: the
  // fifteenth pass's P5). Case-sensitive, as SI prefixes are (M is mega, m milli).
  for (const char* base : {"V", "N", "Pa", "A", "W", "bar", "g"}) {
    const std::string b = base;
    if (t.size() <= b.size() || t.compare(t.size() - b.size(), b.size(), b) != 0) continue;
    const std::string prefix = t.substr(0, t.size() - b.size());
    static const char* const kPrefixes[] = {"q",        "r",        "y", "z", "a", "f",  "p", "n", "u",
                                            "\xc2\xb5", "\xce\xbc", "m", "c", "d", "da", "h", "k", "M",
                                            "G",        "T",        "P", "E", "Z", "Y",  "R", "Q"};
    const bool prefixed =
        std::any_of(std::begin(kPrefixes), std::end(kPrefixes), [&prefix](const char* p) { return prefix == p; });
    const bool known = t == "mV" || t == "kN" || t == "mg";
    if (prefixed && !known) return true;
  }
  if (l == "kgf" || l == "lbm") return true;
  // A degree sign (temperature, angle) is a unit's, never a remark's: "a (\xc2\xb0C)" was read as SI (U095).
  if (t.find("\xc2\xb0") != std::string::npos) return true;
  // A micro sign or an Angstrom sign is a unit's prefix or symbol, never a remark's: "µg", "µin", "Å" (the sixth
  // pass's S035-S056 read them as SI). "µm" and "µm/s" are known before this is asked.
  if ((t.find("\xc2\xb5") != std::string::npos || t.find("\xce\xbc") != std::string::npos ||
       t.find("\xc3\x85") != std::string::npos || t.find("\xe2\x84\xab") != std::string::npos) &&
      known_unit(t, true).empty())
    return true;
  return false;
}

// The bracketed labels of a name, last first: "(g)", "[m/s^2]". An opening bracket with no closing one after it is
// returned in `unclosed`.
std::vector<std::string> bracketed_labels(const std::string& name, std::string* unclosed = nullptr) {
  // A forward scan with a stack, so that nested brackets pair up: the real Impulse_test.lvm names its channel
  // "Acceleration (FFT - (RMS))", whose outer bracket a backward scan for the next closer took as unclosed. A closer
  // without its opener is column_unit_problem's to name. The labels come last-opened first ("x (mm) (raw)" gives raw,
  // mm; a nested label before the one around it).
  std::vector<std::pair<std::size_t, std::string>> labels;  // (opener's position, text inside)
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (c == '(' || c == '[' || c == '{' || c == '<') {
      open.push_back(i);
    } else if (c == ')' || c == ']' || c == '}' || c == '>') {
      if (open.empty()) continue;
      const char o = name[open.back()];
      if ((o == '(' && c != ')') || (o == '[' && c != ']') || (o == '{' && c != '}') || (o == '<' && c != '>'))
        continue;
      labels.emplace_back(open.back(), name.substr(open.back() + 1, i - open.back() - 1));
      open.pop_back();
    }
  }
  if (unclosed && !open.empty()) *unclosed = name.substr(open.front());
  std::sort(labels.begin(), labels.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  // The outermost groups only: a bracket inside a label is part of it ("m/(s^2)", "mm [tip]": label_unit reads it),
  // not a second label (one unit in two brackets was "two units": the sixth pass's S003).
  std::vector<std::string> texts;
  for (const auto& label : labels) {
    // (A named pair, not a structured binding: Clang 14, the fuzz build's compiler, captures none in a lambda.)
    const std::size_t at = label.first, end = label.first + label.second.size() + 1;  // opener's and closer's places
    const bool inside = std::any_of(labels.begin(), labels.end(), [at, end](const auto& other) {
      return other.first < at && other.first + other.second.size() + 1 > end;
    });
    if (!inside) texts.push_back(label.second);
  }
  return texts;
}

// A bracketed label as a unit: known, a unit expression ('/' or '^'), or a unit beamid does not convert, kept as
// stated so that it is refused rather than read as SI; "" for a remark ("accel (tip)").
std::string unit_of_plain_label(const std::string& label);

// A label as a unit, its own brackets and qualifiers read: with an operator ('/', '^') the brackets only group
// ("m/(s^2)", "[mm/s]"); without one, an inner group that states a unit is the unit ("tip (mm)", "(mm)") and one that
// does not is a remark ("mm [tip]"); a peak or RMS qualifier beside a unit leaves the unit ("g pk", "pk-pk mm": the
// sixth pass's S028, S029).
std::string unit_of_label(const std::string& given) {
  std::string label = trimmed(given);
  if (label.find_first_of("([{<") != std::string::npos) {
    if (label.find_first_of("/^") != std::string::npos) {
      // A remark in its own brackets goes first ("mm/s [tip]": it was read as the unit 'mm/s tip', while "mm [tip]"
      // was mm: the seventh pass's U054); the brackets that remain only group.
      for (const std::string& inner : bracketed_labels(label))
        if (inner.find_first_of("/^") == std::string::npos && unit_of_plain_label(inner).empty()) {
          for (const char* pair : {"()", "[]", "{}", "<>"}) {
            const std::string group = std::string(1, pair[0]) + inner + pair[1];
            if (const auto at = label.find(group); at != std::string::npos) label.erase(at, group.size());
          }
        }
      label = trimmed(label);
      std::erase_if(label, [](char c) { return std::string_view("()[]{}<>").find(c) != std::string_view::npos; });
    } else {
      std::string outside;
      std::string inner_unit;
      for (const std::string& inner : bracketed_labels(label))
        if (inner_unit.empty()) inner_unit = unit_of_plain_label(inner);
      int depth = 0;
      for (const char c : label) {
        if (c == '(' || c == '[' || c == '{' || c == '<') ++depth;
        if (depth == 0) outside += c;
        if ((c == ')' || c == ']' || c == '}' || c == '>') && depth > 0) --depth;
      }
      outside = trimmed(outside);
      const std::string outer_unit = unit_of_plain_label(outside);
      if (!outer_unit.empty()) return outer_unit;
      return inner_unit;
    }
  }
  return unit_of_plain_label(label);
}

// A character a remark's word is made of: letters, digits, '-' and '_'.
bool remark_char(unsigned char c) { return std::isalnum(c) != 0 || c == '-' || c == '_'; }

std::string unit_of_plain_label(const std::string& given) {
  std::string label = trimmed(given);
  // A remark beside the unit after ';', ',', ':' or '|' ("mm; tip", "tip, mm", "mm: laser"), read as "mm [tip]" is:
  // the one part that states a unit; two that do are kept as stated, to be refused (the seventh pass's U004, U005
  // and the eighth's U_w07, U_w08 read them as SI). A spaced dash separates as well ("mm - tip").
  for (auto dash = label.find(" - "); dash != std::string::npos; dash = label.find(" - ")) label[dash + 1] = ';';
  if (label.find_first_of(";,:|") != std::string::npos) {
    std::vector<std::string> units;
    for (std::size_t at = 0; at <= label.size();) {
      const std::size_t end = std::min(label.find_first_of(";,:|", at), label.size());
      if (const std::string unit = unit_of_plain_label(label.substr(at, end - at)); !unit.empty())
        units.push_back(unit);
      at = end + 1;
    }
    return units.size() == 1 ? units.front() : units.empty() ? "" : label;
  }
  // A scale factor is part of the unit ("1e-3 m", "10^-3 m", "x1000 mm"): kept as stated, to be refused (U024 read
  // "1e-3 m" as metres).
  const bool numeric_start = !label.empty() && (std::isdigit(static_cast<unsigned char>(label.front())) ||
                                                label.front() == '.' || label.front() == '-' || label.front() == '+');
  if (numeric_start && std::any_of(label.begin(), label.end(), [](unsigned char c) {
        return std::isalpha(c) && c != 'e' && c != 'E';  // a letter beyond an exponent's: a unit after the number
      }))
    return label;
  // A middle dot between words ("mm\xc2\xb7tip", "g\xc2\xb7s") is a space here; known_unit reads "mm\xc2\xb7s-1".
  for (auto dot = label.find("\xc2\xb7"); dot != std::string::npos; dot = label.find("\xc2\xb7"))
    label.replace(dot, 2, " ");
  // Peak and RMS qualifiers ("g pk", "pk-pk mm", "mm/s rms") beside one word that is a unit.
  if (const auto space = label.find(' '); space != std::string::npos) {
    std::vector<std::string> words;
    for (std::size_t at = 0; at < label.size();) {
      const auto next = label.find(' ', at);
      const std::string word = label.substr(at, next == std::string::npos ? std::string::npos : next - at);
      if (!word.empty()) words.push_back(word);
      at = next == std::string::npos ? label.size() : next + 1;
    }
    std::vector<std::string> rest;
    for (const std::string& w : words) {
      const std::string l = lower(w);
      if (l != "pk" && l != "peak" && l != "pk-pk" && l != "p-p" && l != "0-pk" && l != "rms") rest.push_back(w);
    }
    if (rest.size() == 1 && rest.size() < words.size()) label = rest.front();
    const auto is_unit = [](const std::string& w) {
      return !known_unit(w, true).empty() || is_unconverted_unit(w, true);
    };
    if (rest.size() >= 2 && std::all_of(rest.begin(), rest.end(), is_unit)) return label;  // a product: refused
    if (rest.size() >= 2 && known_unit(label, true).empty()) {
      // Two units side by side are their product ("m m" is m^2, not mm, which the spaces' removal made it: U028; "g s"
      // was read as g), kept as stated, to be refused; one unit beside plain words is the unit and a remark ("mm tip",
      // "mm\xc2\xb7tip": the eighth pass's U_w05); anything else is kept as stated.
      int units = 0;
      std::string unit;
      bool plain = true;
      for (const std::string& w : rest) {
        if (!known_unit(w, true).empty() || is_unconverted_unit(w, true)) {
          ++units, unit = known_unit(w, true);
        } else {
          plain = plain && std::all_of(w.begin(), w.end(), [](unsigned char c) { return remark_char(c); });
        }
      }
      if (units == 0) return plain ? "" : label;  // a remark ("sensor 1"), or a unit spelled oddly ("mm/ laser")
      return units == 1 && plain && !unit.empty() ? unit : label;
    }
  }
  // A product or a power written with '*' or a superscript ("mm*mm", "mm\xc2\xb2"), and a unit with a digit stuck to
  // it ("mm2", "g0"): no unit beamid converts, kept as stated, to be refused (the eighth pass's U_w24-U_w31).
  if (known_unit(label, true).empty()) {
    if (label.find('*') != std::string::npos || label.find("\xc2\xb2") != std::string::npos ||
        label.find("\xc2\xb3") != std::string::npos)
      return label;
    const auto digits = label.find_first_of("0123456789");
    if (digits != std::string::npos && digits > 0 && label.find('/') == std::string::npos &&
        !known_unit(label.substr(0, digits), true).empty())
      return label;
  }
  const std::string unit = is_unconverted_unit(label, true) ? "" : known_unit(label, true);
  if (!unit.empty()) return unit;
  if (is_unconverted_unit(label, true) || label.find_first_of("/^") != std::string::npos) return trimmed(label);
  // A remark is words of letters and digits; other characters beside them ("mm~tip", "mm#1", "mm.", a superscript
  // one) spell a unit oddly, which was read as SI (the ninth pass's U-series): kept as stated, to be refused.
  if (!std::all_of(label.begin(), label.end(), [](unsigned char c) { return remark_char(c) || c == ' '; }))
    return trimmed(label);
  return "";
}

// The name before its first bracket ("x_mm" of "x_mm (raw)").
std::string stem_of(const std::string& name) {
  return trimmed(name.substr(0, std::min(name.find_first_of("([{<"), name.size())));
}

// The '_'-separated tokens of a name after its first (the name itself), lower case: "acc_g_raw" gives g, raw.
std::vector<std::string> tokens_after_name(const std::string& name) {
  std::vector<std::string> tokens;
  const std::string n = lower(name);
  for (auto at = n.find('_'); at != std::string::npos;) {
    const auto next = n.find('_', at + 1);
    tokens.push_back(n.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1));
    at = next;
  }
  return tokens;
}

// The unit a name's suffix states ("acc_m_s2" m/s^2, "v_mm_s" mm/s), the longest that spells one, and the position
// of the separator before it; a unit beamid does not convert ("ux_ms", "x_Mm") is returned as written.
std::pair<std::string, std::size_t> suffix_unit(const std::string& name) {
  const std::string n = lower(name);
  for (std::size_t at = 0; (at = n.find('_', at)) != std::string::npos; ++at) {
    // A capital N is newtons ("force_N", what simulate --force-column writes; it had no unit, and a hammer channel
    // resting at 0 between two hits was refused as clipped: the thirty-first pass's adv70 P4); a lower-case n is as
    // likely a name ("x_n").
    if (name.compare(at + 1, std::string::npos, "N") == 0) return {"N", at};
    if (is_unconverted_unit(name.substr(at + 1), false)) return {name.substr(at + 1), at};
    std::string suffix = n.substr(at + 1);
    std::replace(suffix.begin(), suffix.end(), '_', '/');  // m_s2 -> m/s2, mm_s -> mm/s, in_s -> in/s
    for (auto per = suffix.find("/per/"); per != std::string::npos; per = suffix.find("/per/"))
      suffix.replace(per, 5, "/");  // v_mm_per_s (R017)
    if (const std::string unit = known_unit(suffix, false); !unit.empty()) return {unit, at};
    // Units over a time unit that beamid does not convert ("v_m_min": m/min) are kept as written, to be refused
    // (they were read as SI after "min" matched nothing: R016).
    if (const auto slash = suffix.find('/'); slash != std::string::npos &&
                                             !known_unit(suffix.substr(0, slash), false).empty() &&
                                             !time_unit_of_label(suffix.substr(slash + 1)).empty())
      return {suffix, at};
  }
  return {"", std::string::npos};
}

}  // namespace

std::string normalized_unit(std::string_view label) {
  // A capital-M label is mega, kept as stated (refused), in an LVM or UFF label as in a column name (the fifth
  // pass's R088: Y_Unit_Label "Mm" was read as mm).
  if (is_unconverted_unit(std::string(label), true)) return trimmed(label);
  const std::string unit = known_unit(std::string(label), true);
  return unit.empty() ? trimmed(label) : unit;
}

std::string unit_of_column_name(std::string_view column) {
  // The last bracketed label that is a unit: "x (mm) (raw)" is in mm, not SI after its remark "(raw)" (the fifth
  // pass's R005).
  const std::string name = trimmed(column);
  for (const std::string& label : bracketed_labels(name))
    if (const std::string unit = unit_of_label(label); !unit.empty()) return unit;
  const std::string stem = stem_of(name);
  if (const std::string unit = suffix_unit(stem).first; !unit.empty()) return unit;
  // A unit after the name's last space: "v mm/s" (R040); one that spells no unit but is written as one ('/') is kept
  // as stated, to be refused.
  if (const auto space = stem.find_last_of(' '); space != std::string::npos) {
    const std::string last = trimmed(stem.substr(space + 1));
    if (const std::string unit = known_unit(last, false); !unit.empty()) return unit;
    if (last.find('/') != std::string::npos) return last;
  }
  // A unit between the name and a remark: "acc_g_raw" is in g (R043), the last such token.
  const std::vector<std::string> tokens = tokens_after_name(stem);
  for (auto token = tokens.rbegin(); token != tokens.rend(); ++token)
    if (const std::string unit = known_unit(*token, false); !unit.empty()) return unit;
  return "";
}

std::string column_unit_problem(std::string_view column) {
  const std::string name = trimmed(column);
  std::string unclosed;
  const auto labels = bracketed_labels(name, &unclosed);
  if (!unclosed.empty())
    return "'" + unclosed + "' opens a bracket that does not close: write the unit as 'name (unit)'";
  if (std::count(name.begin(), name.end(), ')') > std::count(name.begin(), name.end(), '(') ||
      std::count(name.begin(), name.end(), ']') > std::count(name.begin(), name.end(), '['))
    return "a bracket closes that no bracket opened: write the unit as 'name (unit)'";
  // Every unit the name states, bracketed or as a suffix of the name before the first bracket.
  std::vector<std::string> units;
  for (const auto& label : labels)
    if (const std::string unit = unit_of_label(label); !unit.empty()) units.push_back(unit);
  const std::string stem = stem_of(name);
  const auto [unit, at] = suffix_unit(stem);
  if (!unit.empty()) units.push_back(unit);
  // "x_mm_um": a known unit between the name and its suffix unit.
  if (at != std::string::npos)
    for (const std::string& token : tokens_after_name(stem.substr(0, at)))
      if (const std::string u = known_unit(token, false); !u.empty()) units.push_back(u);
  for (const auto& u : units)
    if (u != units.front()) return "it states two units, " + units.front() + " and " + u + ": name the column with one";
  // A name ending in "_in" with no other unit: inches, or an input ("force_in")? Read as SI, a displacement in inches
  // was 25.4x off and its fit silently wrong (the thirteenth pass's 1): the user says which.
  const std::string l = lower(stem);
  if (units.empty() && l.size() > 3 && l.compare(l.size() - 3, 3, "_in") == 0)
    return "its name ends in '_in', inches or an input: write the unit as 'name (in)' for inches (converted to m), "
           "or rename it";
  return "";
}

std::string time_unit_of_column_name(std::string_view column) {
  // The last bracketed label that is a unit of any kind ("t (ms) [rel]" is in ms: the fifth pass's R061); one that
  // is no time unit ("t (Hz)", "t (m)") is returned as written, for the caller to refuse.
  const std::string name = trimmed(column);
  for (const std::string& label : bracketed_labels(name)) {
    if (const std::string unit = time_unit_of_label(label); !unit.empty()) return unit;
    if (!unit_of_label(label).empty() || lower(trimmed(label)) == "hz") return trimmed(label);
  }
  // The suffix, or a time unit between the name and a remark ("t_ms_abs"): the last such token.
  const std::vector<std::string> tokens = tokens_after_name(stem_of(name));
  for (auto token = tokens.rbegin(); token != tokens.rend(); ++token)
    if (const std::string unit = time_unit_of_label(*token); !unit.empty()) return unit;
  return "";
}

std::string time_unit_of_label(std::string_view text) {
  const std::string label = lower(trimmed(text));
  // Time units' spellings: a named array (not a braced temporary: GCC and Clang read doubled braces differently).
  static constexpr std::pair<const char*, const char*> spellings[] = {
      {"s", "s"},       {"secs", "s"},          {"second", "s"},     {"millisecond", "ms"}, {"milliseconds", "ms"},
      {"msecs", "ms"},  {"microseconds", "us"}, {"hr", "h"},         {"hrs", "h"},          {"hour", "h"},
      {"days", "days"}, {"sec", "s"},           {"seconds", "s"},    {"ms", "ms"},          {"msec", "ms"},
      {"us", "us"},     {"usec", "us"},         {"\xc2\xb5s", "us"}, {"ns", "ns"},          {"min", "min"},
      {"mins", "min"},  {"minutes", "min"},     {"h", "h"},          {"hours", "h"}};
  for (const auto& [spelling, unit] : spellings)
    if (label == spelling) return unit;
  return "";
}

std::optional<SiConversion> si_conversion(const std::string& unit) {
  if (unit == "g") return SiConversion{"m/s^2", kStandardGravity};
  if (unit == "mg") return SiConversion{"m/s^2", 1e-3 * kStandardGravity};
  if (unit == "cm") return SiConversion{"m", 1e-2};
  if (unit == "mm") return SiConversion{"m", 1e-3};
  if (unit == "um") return SiConversion{"m", 1e-6};
  if (unit == "in") return SiConversion{"m", kInch};
  if (unit == "mm/s") return SiConversion{"m/s", 1e-3};
  if (unit == "in/s") return SiConversion{"m/s", kInch};
  if (unit == "mm/s^2") return SiConversion{"m/s^2", 1e-3};
  if (unit == "in/s^2") return SiConversion{"m/s^2", kInch};
  if (unit == "nm") return SiConversion{"m", 1e-9};
  if (unit == "pm") return SiConversion{"m", 1e-12};
  if (unit == "km") return SiConversion{"m", 1e3};
  if (unit == "yd") return SiConversion{"m", 3 * kFoot};
  if (unit == "mil") return SiConversion{"m", 1e-3 * kInch};
  if (unit == "mph") return SiConversion{"m/s", 1609.344 / 3600};  // the international mile, 1760 yd
  if (unit == "Gal") return SiConversion{"m/s^2", 1e-2};           // the gal, 1 cm/s^2
  if (unit == "ft") return SiConversion{"m", kFoot};
  if (unit == "ft/s") return SiConversion{"m/s", kFoot};
  if (unit == "ft/s^2") return SiConversion{"m/s^2", kFoot};
  if (unit == "km/h") return SiConversion{"m/s", 1 / 3.6};
  if (unit == "um/s") return SiConversion{"m/s", 1e-6};
  if (unit == "cm/s") return SiConversion{"m/s", 1e-2};
  return std::nullopt;
}

std::string quantity_of(const std::string& unit) {
  const auto si = si_conversion(unit);
  const std::string base = si ? si->unit : unit;
  if (base == "m") return "displacement";
  if (base == "m/s") return "velocity";
  if (base == "m/s^2") return "acceleration";
  return "";
}

bool is_force_unit(const std::string& unit) { return unit == "N" || unit == "kN" || unit == "lbf"; }

bool is_non_motion_unit(const std::string& unit) {
  return unit == "V" || unit == "mV" || is_force_unit(unit) || unit == "Pa";
}

bool is_known_unit(const std::string& unit) {
  return unit == "m" || unit == "m/s" || unit == "m/s^2" || si_conversion(unit) || is_non_motion_unit(unit);
}

std::string known_units_list() {
  return "m, km, cm, mm, um, nm, pm, in, mil, ft, yd; m/s, cm/s, mm/s, um/s, in/s, ft/s, km/h, mph; m/s^2, mm/s^2, "
         "in/s^2, "
         "ft/s^2, Gal, g, mg; V, mV, N, kN, lbf, Pa";
}

}  // namespace beamid::io
