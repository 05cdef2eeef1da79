// Reading the paper's published values (see the header).
#include "analysis/paper_values.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "util/toml_locator.h"

namespace fs = std::filesystem;

namespace ra::analysis {

bool PaperDifference::covers(const std::string& table, const std::string& statistic,
                             const std::string& group, const std::string& platform) const {
  const auto in = [](const std::vector<std::string>& list, const std::string& x) {
    return list.empty() || std::find(list.begin(), list.end(), x) != list.end();
  };
  return in(tables, table) && in(statistics, statistic) && in(groups, group) &&
         platform.find(platform_contains) != std::string::npos;
}

namespace {

constexpr double kLargestPaperValue = 1e15;

// [[difference]] entries: lists of strings checked against what they may hold.
std::vector<PaperDifference> read_differences(const util::TomlLocator& loc,
                                              const toml::table& root) {
  std::vector<PaperDifference> out;
  const toml::node* node = root.get("difference");
  if (!node) return out;
  const toml::array* list = node->as_array();
  if (!list) loc.fail(node, "difference: one [[difference]] per explanation");
  for (const toml::node& entry : *list) {
    const toml::table* t = entry.as_table();
    if (!t) loc.fail(&entry, "difference: each entry must be a [[difference]]");
    loc.reject_unknown_keys(*t, "difference.",
                            {"tables", "statistics", "groups", "platform_contains", "explanation"});
    PaperDifference d;
    auto strings = [&](const char* key, std::vector<std::string> allowed) {
      std::vector<std::string> v;
      const toml::node* n = t->get(key);
      if (!n) return v;
      const toml::array* a = n->as_array();
      if (!a) loc.fail(n, std::string("difference.") + key + ": a list of strings");
      for (const toml::node& x : *a) {
        const auto s = x.value<std::string>();
        bool ok = s.has_value();
        if (ok && !allowed.empty())
          ok = std::find(allowed.begin(), allowed.end(), *s) != allowed.end();
        if (!ok) {
          std::string allowed_text;
          for (const std::string& a_ : allowed) allowed_text += (allowed_text.empty() ? "" : ", ") + a_;
          loc.fail(&x, std::string("difference.") + key + ": a string" +
                           (allowed.empty() ? "" : " (allowed: " + allowed_text + ")"));
        }
        v.push_back(*s);
      }
      return v;
    };
    d.tables = strings("tables", {});
    d.statistics = strings("statistics", {"median", "IQR"});
    d.groups = strings("groups", {"A", "B", "C", "D"});
    d.platform_contains = (*t)["platform_contains"].value_or(std::string());
    const auto text = (*t)["explanation"].value<std::string>();
    if (!text || text->empty()) loc.fail(t, "difference.explanation: missing (a string)");
    d.explanation = *text;
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace

PaperValues load_paper_values(const std::string& path) {
  const util::TomlLocator loc(path);
  const toml::table root =
      loc.parse(util::TomlLocator::read_text(path, "the paper's values (--paper)"));
  loc.reject_unknown_keys(root, "", {"table", "difference", "primitives_per_view_group"});
  PaperValues values;
  if (const toml::node* n = root.get("primitives_per_view_group"))
    values.primitives_per_view_group =
        double(loc.integer(*n, "primitives_per_view_group", 1, 1000000000000));
  values.differences = read_differences(loc, root);
  const toml::array* tables = root["table"].as_array();
  if (!tables) loc.fail(&root, "no [[table]] (allowed: one [[table]] per paper table)");
  std::vector<PaperTableValues>& out = values.tables;
  for (const toml::node& node : *tables) {
    const toml::table* t = node.as_table();
    if (!t) loc.fail(&node, "table: each entry must be a [[table]]");
    loc.reject_unknown_keys(
        *t, "table.",
        {"number", "column", "scale_exponent", "page", "reading", "fov_deg", "window",
         "platform_1_median", "platform_2_median", "platform_1_iqr", "platform_2_iqr"});
    PaperTableValues v;
    auto text = [&](const char* key) {
      const auto s = (*t)[key].value<std::string>();
      if (!s) loc.fail(t, std::string("table.") + key + ": missing (a string)");
      return *s;
    };
    auto four = [&](const char* key) {
      const toml::array* a = (*t)[key].as_array();
      if (!a || a->size() != 4)
        loc.fail(a ? static_cast<const toml::node*>(a) : t,
                 std::string("table.") + key + ": four numbers, groups A-D (nan for a lost cell)");
      std::array<double, 4> x{};
      for (int i = 0; i < 4; ++i) {
        x[i] = loc.number(*a->get(i), std::string("table.") + key);
        // a printed table value: finite (nan marks a lost cell), and small enough that no
        // scaling or difference taken from it overflows
        if (std::isinf(x[i]) || std::fabs(x[i]) > kLargestPaperValue)
          loc.fail(a->get(i), std::string("table.") + key + ": value " + std::to_string(i + 1) +
                                  " of 4 is not a table value (allowed: -1e15 to 1e15, or nan "
                                  "for a lost cell)");
      }
      return x;
    };
    v.number = text("number");
    v.column = text("column");
    v.reading = text("reading");
    const toml::node* exponent = t->get("scale_exponent");
    if (!exponent) loc.fail(t, "table.scale_exponent: missing (an integer, -12 to 12)");
    v.scale_exponent = int(loc.integer(*exponent, "table.scale_exponent", -12, 12));
    v.page = t->contains("page") ? int(loc.integer(*t->get("page"), "table.page", 0, 100000)) : 0;
    v.fov_deg = four("fov_deg");
    v.window = four("window");
    v.median = {four("platform_1_median"), four("platform_2_median")};
    v.iqr = {four("platform_1_iqr"), four("platform_2_iqr")};
    out.push_back(std::move(v));
  }
  return values;
}

std::string default_paper_values_path() {
  const std::string relative = "experiments/papers/nist2008-tables.toml";
  std::error_code ec;
  if (fs::exists(relative, ec)) return relative;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = exe.parent_path().parent_path() / relative;  // build/renderaudit
    if (fs::exists(beside, ec)) return beside.string();
    const fs::path installed =  // PREFIX/bin/renderaudit (`make install`)
        exe.parent_path().parent_path() / "share" / "renderaudit" / relative;
    if (fs::exists(installed, ec)) return installed.string();
  }
  return "";
}

}  // namespace ra::analysis
