// Reading the paper's published values (see the header).
#include "analysis/paper_values.h"

#include <cmath>
#include <filesystem>

#include "util/toml_locator.h"

namespace fs = std::filesystem;

namespace ra::analysis {

std::vector<PaperTableValues> load_paper_values(const std::string& path) {
  const TomlLocator loc(path);
  const toml::table root = loc.parse(TomlLocator::read_text(path));
  loc.reject_unknown_keys(root, "", {"table"});
  const toml::array* tables = root["table"].as_array();
  if (!tables) loc.fail(&root, "no [[table]] (allowed: one [[table]] per paper table)");
  std::vector<PaperTableValues> out;
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
      for (int i = 0; i < 4; ++i) x[i] = loc.number(*a->get(i), std::string("table.") + key);
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
  return out;
}

std::string default_paper_values_path() {
  const std::string relative = "experiments/papers/nist2008-tables.toml";
  std::error_code ec;
  if (fs::exists(relative, ec)) return relative;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = exe.parent_path().parent_path() / relative;
    if (fs::exists(beside, ec)) return beside.string();
  }
  return "";
}

}  // namespace ra::analysis
