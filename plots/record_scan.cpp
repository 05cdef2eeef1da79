// One fast pass over the records for conformance and non-ok cases (see the header).
#include "plots/record_scan.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string_view>
#include <thread>

#include "util/errors.h"
#include "metrics/records.h"

namespace fs = std::filesystem;

namespace ra::plots {
namespace {

struct Columns {
  std::size_t platform, view, view_group, fov, width, height, kind, index, status, visibility,
      pixels, ref_diff, render_us;
  std::size_t count;
};

Columns locate_columns() {
  std::vector<std::string> names;
  std::stringstream ss(records_header());
  std::string n;
  while (std::getline(ss, n, ',')) names.push_back(n);
  auto at = [&](const char* name) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw std::logic_error(std::string("records header lacks ") + name);
    return std::size_t(it - names.begin());
  };
  return {at("platform"), at("view"),  at("view_group"), at("fov_deg"),
          at("width"),    at("height"), at("kind"),      at("index"),
          at("status"),   at("visibility"), at("pixels"), at("ref_diff"), at("render_us"),
          names.size()};
}

template <typename T>
T parse_int(std::string_view s, const std::string& where, const char* column) {
  T v{};
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size())
    throw UserError(where + ": column '" + column + "': '" + std::string(s) +
                    "' is not an integer");
  return v;
}

struct Partial {
  RecordScan scan;
  std::vector<NonOkCase> examples;
};

void scan_file(const fs::path& path, const std::string& rel, const Columns& c,
               std::size_t max_examples, Partial& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("cannot read " + path.string());
  std::string line;
  if (!std::getline(in, line)) throw UserError(path.string() + ":1: empty records file");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != records_header())
    throw UserError(path.string() + ":1: unexpected records header (expected: " +
                    records_header() + ")");
  std::vector<std::string_view> f(c.count);
  std::size_t lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;  // '#': the seal of a shard file
    std::size_t k = 0, start = 0;
    for (std::size_t i = 0; i <= line.size() && k < c.count; ++i)
      if (i == line.size() || line[i] == ',') {
        f[k++] = std::string_view(line).substr(start, i - start);
        start = i + 1;
      }
    const std::string where = path.string() + ":" + std::to_string(lineno);
    if (k != c.count) throw UserError(where + ": expected " + std::to_string(c.count) + " cells");
    ++out.scan.records;
    const std::string platform(f[c.platform]), kind(f[c.kind]);
    const int group = parse_int<int>(f[c.view_group], where, "view_group");
    const auto key = std::make_tuple(platform, kind, group);
    if (!out.scan.group_labels.count(key))
      out.scan.group_labels[key] = std::string(f[c.fov]) + " deg, " + std::string(f[c.width]) +
                                   "x" + std::string(f[c.height]);
    if (f[c.status] != "ok") {
      ++out.scan.non_ok_counts[{platform, kind, std::string(f[c.status])}];
      if (out.examples.size() < max_examples)
        out.examples.push_back({platform, kind, std::string(f[c.status]),
                                parse_int<int>(f[c.view], where, "view"),
                                parse_int<std::uint64_t>(f[c.index], where, "index"), rel,
                                lineno});
      continue;
    }
    if (!f[c.render_us].empty()) {
      double us = 0;
      const auto r = std::from_chars(f[c.render_us].data(), f[c.render_us].data() + f[c.render_us].size(), us);
      if (r.ec != std::errc() || r.ptr != f[c.render_us].data() + f[c.render_us].size())
        throw UserError(where + ": column 'render_us': '" + std::string(f[c.render_us]) +
                        "' is not a number");
      out.scan.render_us[{platform, kind}].push_back(us);
      if (f[c.visibility] == "true-visible") out.scan.render_us_visible[{platform, kind}].push_back(us);
    }
    if (f[c.ref_diff].empty()) continue;
    const auto diff = parse_int<long long>(f[c.ref_diff], where, "ref_diff");
    const auto pixels = f[c.pixels].empty() ? 0 : parse_int<long long>(f[c.pixels], where, "pixels");
    Conformance& cf = out.scan.conformance[key];
    ++cf.compared;
    cf.identical += diff == 0;
    if (pixels > 0 || diff > 0) {
      ++cf.drawn;
      cf.drawn_identical += diff == 0;
    }
  }
}

}  // namespace

RecordScan scan_records(const std::string& run_dir, std::size_t max_examples, unsigned jobs) {
  const fs::path dir = fs::path(run_dir) / "records";
  if (!fs::is_directory(dir)) throw UserError(run_dir + ": no records directory (" + dir.string() + ")");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".csv") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw UserError(dir.string() + ": no records files (*.csv)");

  const Columns c = locate_columns();
  if (jobs == 0) jobs = std::max(1u, std::thread::hardware_concurrency());
  jobs = std::min<unsigned>(jobs, unsigned(files.size()));
  std::vector<Partial> parts(files.size());
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<std::thread> threads;
  for (unsigned t = 0; t < jobs; ++t)
    threads.emplace_back([&] {
      for (std::size_t i; (i = next++) < files.size();) {
        try {
          scan_file(files[i], fs::relative(files[i], run_dir).string(), c, max_examples, parts[i]);
        } catch (...) {
          std::lock_guard<std::mutex> lock(error_mutex);
          if (!error) error = std::current_exception();
        }
      }
    });
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);

  RecordScan out;
  out.files = files.size();
  for (auto& p : parts) {
    out.records += p.scan.records;
    for (const auto& [k, v] : p.scan.conformance) {
      Conformance& cf = out.conformance[k];
      cf.compared += v.compared;
      cf.identical += v.identical;
      cf.drawn += v.drawn;
      cf.drawn_identical += v.drawn_identical;
    }
    for (const auto& [k, v] : p.scan.non_ok_counts) out.non_ok_counts[k] += v;
    for (const auto& [k, v] : p.scan.group_labels) out.group_labels.emplace(k, v);
    for (auto& [k, v] : p.scan.render_us) {
      auto& all = out.render_us[k];
      all.insert(all.end(), v.begin(), v.end());
    }
    for (auto& [k, v] : p.scan.render_us_visible) {
      auto& all = out.render_us_visible[k];
      all.insert(all.end(), v.begin(), v.end());
    }
    for (auto& e : p.examples)
      if (out.non_ok_examples.size() < max_examples) out.non_ok_examples.push_back(std::move(e));
  }
  return out;
}

}  // namespace ra::plots
