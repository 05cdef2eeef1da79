// A run's verdicts against an expectations file (see the header).
#include "analysis/conformance_expectations.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "geometry/primitive.h"
#include "metrics/records.h"
#include "rundir/experiment.h"
#include "rundir/records_format.h"
#include "rundir/records_reader.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "util/errors.h"
#include "util/number_text.h"
#include "util/program_name.h"
#include "util/shell_quote.h"
#include "util/xml_text.h"

namespace fs = std::filesystem;

namespace ra::analysis {
namespace {

using Key =
    std::tuple<std::string, std::string, int, std::uint64_t>;  // platform, kind, view, index

std::string primitive_name(const std::string& platform, const std::string& kind, int view,
                           std::uint64_t index) {
  return platform + " " + kind + " " + std::to_string(view) + " " + std::to_string(index);
}

// The errors of a file, all said at once: a reviewer fixes every line in one go.
void throw_if_any(const std::vector<std::string>& errors) {
  if (errors.empty()) return;
  std::string all;
  for (const std::string& e : errors) all += (all.empty() ? "" : "\n") + e;
  throw util::UserError(all);
}

template <typename Int>
bool parse_whole(const std::string& s, Int* out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

int kind_order(const std::string& kind) {
  geometry::Kind k{};
  return geometry::parse_kind(kind, &k) ? int(k) : 3;
}

std::string show_command(const std::string& run_dir, const std::string& platform,
                         const std::string& kind, int view, std::uint64_t index) {
  return util::program_for_commands() + " " +
         util::shell_command({"show", run_dir, "-p", platform, "-k", kind, "-v",
                              std::to_string(view), "-i", std::to_string(index)});
}

std::string xml(const std::string& s) { return util::xml_text(s); }

std::string plural(std::size_t n, const std::string& one, const std::string& many) {
  return util::grouped(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string ExpectedViolation::name() const { return primitive_name(platform, kind, view, index); }
std::string FoundViolation::name() const { return primitive_name(platform, kind, view, index); }

std::size_t ConformanceCase::new_count() const {
  return std::size_t(std::count_if(violations.begin(), violations.end(),
                                   [](const FoundViolation& v) { return v.expected_at == 0; }));
}

std::uint64_t ConformanceCheck::judged() const {
  std::uint64_t n = 0;
  for (const ConformanceCase& c : cases) n += c.judged;
  return n;
}
std::size_t ConformanceCheck::violations() const {
  std::size_t n = 0;
  for (const ConformanceCase& c : cases) n += c.violations.size();
  return n;
}
std::size_t ConformanceCheck::new_violations() const {
  std::size_t n = 0;
  for (const ConformanceCase& c : cases) n += c.new_count();
  return n;
}
std::size_t ConformanceCheck::fixed() const {
  std::size_t n = 0;
  for (const ConformanceCase& c : cases) n += c.fixed.size();
  return n;
}
std::size_t ConformanceCheck::not_judged() const {
  std::size_t n = platform_not_run.size();
  for (const ConformanceCase& c : cases) n += c.not_judged.size();
  return n;
}

Expectations parse_expectations(const std::string& text, const std::string& path) {
  Expectations e;
  e.path = path;
  std::vector<std::string> errors;
  std::map<Key, int> seen;  // -> line
  std::istringstream in(text);
  std::string raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string at = path + ":" + std::to_string(line) + ": ";
    std::string content = raw.substr(0, raw.find('#'));
    std::istringstream words(content);
    std::vector<std::string> f;
    for (std::string w; words >> w;) f.push_back(w);
    if (f.empty()) continue;
    if (f.size() != 4) {
      errors.push_back(at +
                       "expected four fields, PLATFORM KIND VIEW INDEX (e.g. "
                       "'osmesa-softpipe line 5 721'), found " +
                       std::to_string(f.size()) + ": '" +
                       content.substr(0, content.find_last_not_of(" \t\r") + 1) +
                       "'; write the line so, or start it with '#'");
      continue;
    }
    ExpectedViolation v;
    v.platform = f[0];
    v.kind = f[1];
    v.line = line;
    bool ok = true;
    if (f[1] != "point" && f[1] != "line" && f[1] != "triangle") {
      errors.push_back(at + "kind '" + f[1] + "' is not one of point, line, triangle");
      ok = false;
    }
    if (!parse_whole(f[2], &v.view) || v.view < 1) {
      errors.push_back(at + "view '" + f[2] + "' is not a view id (1, 2, ...)");
      ok = false;
    }
    if (!parse_whole(f[3], &v.index)) {
      errors.push_back(at + "index '" + f[3] + "' is not a primitive index (0, 1, ...)");
      ok = false;
    }
    if (!ok) continue;
    const auto [it, fresh] = seen.emplace(Key{v.platform, v.kind, v.view, v.index}, line);
    if (!fresh) {
      errors.push_back(at + v.name() + " is listed already on line " + std::to_string(it->second) +
                       "; remove one of the two");
      continue;
    }
    e.entries.push_back(v);
  }
  throw_if_any(errors);
  return e;
}

Expectations read_expectations(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw util::UserError(path + ": cannot read the expectations file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_expectations(text.str(), path);
}

ConformanceCheck check_conformance(const std::string& run_dir, const Expectations* expectations) {
  const rundir::Experiment exp = rundir::load_run_experiment(run_dir);
  ConformanceCheck check;
  check.run_dir = run_dir;
  check.experiment = exp.name;
  check.experiment_hash = exp.hash;
  if (expectations) check.expectations_path = expectations->path;

  // A line naming what the experiment does not have cannot be judged: said, with its place.
  std::map<Key, const ExpectedViolation*> listed;
  if (expectations) {
    std::vector<std::string> errors;
    std::string platforms;
    for (const std::string& p : exp.platforms) platforms += (platforms.empty() ? "" : ", ") + p;
    for (const ExpectedViolation& v : expectations->entries) {
      const std::string at = expectations->path + ":" + std::to_string(v.line) + ": ";
      geometry::Kind kind{};
      geometry::parse_kind(v.kind, &kind);
      if (std::find(exp.platforms.begin(), exp.platforms.end(), v.platform) == exp.platforms.end())
        errors.push_back(at + "platform '" + v.platform + "' is not in the experiment of " +
                         run_dir + " (its platforms: " + platforms +
                         "); remove the line, or correct the name");
      else if (std::none_of(exp.views.begin(), exp.views.end(),
                            [&](const geometry::View& w) { return w.id == v.view; }))
        errors.push_back(at + "view " + std::to_string(v.view) + " is not in the experiment of " +
                         run_dir + " (views 1 to " + std::to_string(exp.views.size()) +
                         "); remove the line: it was written for another experiment");
      else if (v.index >= exp.counts[std::size_t(kind)])
        errors.push_back(at + "index " + std::to_string(v.index) + " is past the " +
                         util::grouped(exp.counts[std::size_t(kind)]) + " " + v.kind +
                         "s per view of the experiment of " + run_dir +
                         "; remove the line: it was written for another experiment");
      else
        listed.emplace(Key{v.platform, v.kind, v.view, v.index}, &v);
    }
    throw_if_any(errors);
  }

  std::map<std::string, std::size_t> platform_order;
  for (std::size_t i = 0; i < exp.platforms.size(); ++i) platform_order[exp.platforms[i]] = i;
  std::map<int, const geometry::View*> views;
  for (const geometry::View& v : exp.views) views[v.id] = &v;
  // (platform order, kind, view) -> case
  std::map<std::tuple<std::size_t, int, int>, ConformanceCase> cases;
  std::map<Key, bool> seen_listed;  // listed primitives that have a record

  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::records(run_dir), ec))
    if (rundir::is_records_file_name(e.path().filename().string()))
      files.push_back(e.path().string());
  if (ec)
    throw util::UserError(rundir::run_folder::records(run_dir) + ": cannot read (" + ec.message() +
                          ")");
  std::sort(files.begin(), files.end());
  using C = metrics::RecordColumn;
  for (const std::string& file : files) {
    rundir::for_each_record_row(file, [&](const rundir::RecordRow& row) {
      const std::string platform(row.cell(C::kPlatform)), kind(row.cell(C::kKind));
      const int view = row.integer<int>(C::kView);
      const auto order = platform_order.find(platform);
      if (order == platform_order.end())
        row.fail("platform '" + platform + "' is not in the run's experiment");
      ConformanceCase& c = cases[{order->second, kind_order(kind), view}];
      if (c.records == 0) {
        c.platform = platform, c.kind = kind, c.view = view;
        if (const auto w = views.find(view); w != views.end())
          c.view_label = util::format_text("%g deg, %dx%d", w->second->fov_deg, w->second->width,
                                           w->second->height);
      }
      ++c.records;
      const metrics::CaseStatus status = row.status();
      const metrics::Conformance verdict = row.conformance();
      const bool judged =
          status == metrics::CaseStatus::kOk && verdict != metrics::Conformance::kNotCompared;
      c.judged += judged;
      const std::uint64_t index = row.integer<std::uint64_t>(C::kIndex);
      const auto l = listed.find(Key{platform, kind, view, index});
      if (l != listed.end()) seen_listed[l->first] = true;
      if (judged && verdict == metrics::Conformance::kViolation) {
        FoundViolation v;
        v.platform = platform, v.kind = kind, v.view = view, v.index = index;
        v.violating_pixels = row.optional_integer<std::int64_t>(C::kViolatingPixels, 0);
        v.rules = std::string(row.cell(C::kViolatedRules));
        if (l != listed.end()) v.expected_at = l->second->line;
        c.violations.push_back(v);
      } else if (l != listed.end()) {
        ListedOutcome o{*l->second, "no verdict"};
        if (judged)
          o.now = metrics::conformance_name(verdict);
        else if (status != metrics::CaseStatus::kOk)
          o.now = std::string("recorded as ") + metrics::status_name(status);
        (judged ? c.fixed : c.not_judged).push_back(o);
      }
    });
  }
  std::map<std::string, bool> platform_drawn;
  for (const auto& [key, c] : cases) platform_drawn[c.platform] = true;
  for (const auto& [key, v] : listed) {
    if (seen_listed.count(key)) continue;
    if (!platform_drawn.count(v->platform)) {
      check.platform_not_run.push_back(*v);
      continue;
    }
    geometry::Kind kind{};
    geometry::parse_kind(v->kind, &kind);
    ConformanceCase& c = cases[{platform_order[v->platform], int(kind), v->view}];
    if (c.records == 0) c.platform = v->platform, c.kind = v->kind, c.view = v->view;
    c.not_judged.push_back({*v, "no record in the run"});
  }
  for (auto& [key, c] : cases) {
    std::sort(c.violations.begin(), c.violations.end(),
              [](const FoundViolation& a, const FoundViolation& b) { return a.index < b.index; });
    const auto by_index = [](const ListedOutcome& a, const ListedOutcome& b) {
      return a.listed.index < b.listed.index;
    };
    std::sort(c.fixed.begin(), c.fixed.end(), by_index);
    std::sort(c.not_judged.begin(), c.not_judged.end(), by_index);
    check.cases.push_back(std::move(c));
  }
  std::sort(check.platform_not_run.begin(), check.platform_not_run.end(),
            [](const ExpectedViolation& a, const ExpectedViolation& b) { return a.line < b.line; });
  return check;
}

std::string expectations_text(const ConformanceCheck& c) {
  std::string out =
      "# Known violations of the rasterization rules (docs/conformance.md), one primitive per\n"
      "# line: PLATFORM KIND VIEW INDEX. `renderaudit conformance RUN --expectations FILE` passes\n"
      "# on these, fails on any other violation and reports those no longer violations.\n"
      "# Written by `renderaudit conformance --write-expectations` from a run of the experiment\n"
      "# with hash " +
      c.experiment_hash + ": the indices name primitives of that experiment only.\n";
  for (const ConformanceCase& k : c.cases)
    for (const FoundViolation& v : k.violations)
      out += v.name() + "  # " + std::to_string(v.violating_pixels) + " px: " + v.rules + "\n";
  return out;
}

std::string conformance_junit(const ConformanceCheck& c) {
  struct Suite {
    std::string platform;
    std::string body;
    std::size_t tests = 0, failures = 0, skipped = 0;
  };
  std::vector<Suite> suites;
  for (const ConformanceCase& k : c.cases) {
    if (suites.empty() || suites.back().platform != k.platform) {
      suites.emplace_back();
      suites.back().platform = k.platform;
    }
    Suite& s = suites.back();
    ++s.tests;
    std::ostringstream tc;
    tc << "    <testcase classname=\"renderaudit.conformance." << xml(k.platform) << "."
       << xml(k.kind) << "\" name=\"view " << k.view
       << (k.view_label.empty() ? "" : " (" + xml(k.view_label) + ")") << "\" time=\"0\">\n";
    const std::size_t fresh = k.new_count();
    tc << "      <properties>\n";
    for (const auto& [name, value] :
         std::vector<std::pair<std::string, std::size_t>>{{"judged", k.judged},
                                                          {"violations", k.violations.size()},
                                                          {"known", k.violations.size() - fresh},
                                                          {"new", fresh},
                                                          {"fixed", k.fixed.size()}})
      tc << "        <property name=\"" << name << "\" value=\"" << value << "\"/>\n";
    tc << "      </properties>\n";
    std::string known, fixed;
    std::ostringstream fresh_text;
    for (const FoundViolation& v : k.violations) {
      const std::string line = v.name() + ": " + std::to_string(v.violating_pixels) +
                               " violating pixel(s) (" + v.rules + "); " +
                               show_command(c.run_dir, v.platform, v.kind, v.view, v.index) + "\n";
      if (v.expected_at)
        known +=
            "known (" + c.expectations_path + ":" + std::to_string(v.expected_at) + "): " + line;
      else
        fresh_text << line;
    }
    for (const ListedOutcome& o : k.fixed)
      fixed += "fixed (" + c.expectations_path + ":" + std::to_string(o.listed.line) +
               "): " + o.listed.name() + " is now " + o.now + "\n";
    for (const ListedOutcome& o : k.not_judged)
      fixed += "not judged (" + c.expectations_path + ":" + std::to_string(o.listed.line) +
               "): " + o.listed.name() + ": " + o.now + "\n";
    if (fresh) {
      ++s.failures;
      tc << "      <failure type=\"violation\" message=\""
         << xml(plural(fresh, "primitive breaks", "primitives break") + " a rasterization rule" +
                (c.expectations_path.empty() ? "" : ", not listed in " + c.expectations_path))
         << "\">" << xml(fresh_text.str()) << "</failure>\n";
    } else if (k.judged == 0) {
      ++s.skipped;
      tc << "      <skipped message=\"no verdict: nothing judged (the reference platform, or no "
            "record drawn)\"/>\n";
    }
    if (!known.empty() || !fixed.empty())
      tc << "      <system-out>" << xml(known + fixed) << "</system-out>\n";
    tc << "    </testcase>\n";
    s.body += tc.str();
  }
  std::size_t tests = 0, failures = 0, skipped = 0;
  for (const Suite& s : suites) tests += s.tests, failures += s.failures, skipped += s.skipped;
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"renderaudit "
         "conformance\" tests=\""
      << tests << "\" failures=\"" << failures << "\" errors=\"0\" skipped=\"" << skipped
      << "\">\n";
  for (const Suite& s : suites)
    out << "  <testsuite name=\"" << xml(s.platform) << "\" tests=\"" << s.tests << "\" failures=\""
        << s.failures << "\" errors=\"0\" skipped=\"" << s.skipped << "\">\n"
        << s.body << "  </testsuite>\n";
  out << "</testsuites>\n";
  return out.str();
}

std::string conformance_text(const ConformanceCheck& c, bool verdict, std::size_t limit) {
  const std::size_t all = c.violations(), fresh = c.new_violations(), fixed = c.fixed();
  const std::string file = c.expectations_path;
  std::string out = "conformance: " + c.run_dir + ": " + util::grouped(c.judged()) +
                    " primitives judged, " + plural(all, "violation", "violations");
  if (!file.empty())
    out += " (" + util::grouped(all - fresh) + " listed in " + file + ", " + util::grouped(fresh) +
           " new; " + plural(fixed, "listed primitive", "listed primitives") + " no longer " +
           (fixed == 1 ? "a violation" : "violations") + ")";
  out += "\n";
  if (!verdict) return out;
  std::size_t said = 0;
  for (const ConformanceCase& k : c.cases)
    for (const FoundViolation& v : k.violations)
      if (!v.expected_at && said++ < limit)
        out += "new: " + v.name() + ": " + std::to_string(v.violating_pixels) + " violating px (" +
               v.rules + "): " + show_command(c.run_dir, v.platform, v.kind, v.view, v.index) +
               "\n";
  if (said > limit)
    out += "  and " + util::grouped(said - limit) +
           " more new (each in the JUnit file, --junit FILE, and in --write-expectations FILE)\n";
  for (const ConformanceCase& k : c.cases) {
    for (const ListedOutcome& o : k.fixed)
      out += "fixed: " + o.listed.name() + " (" + file + ":" + std::to_string(o.listed.line) +
             ") is now " + o.now + ": remove its line\n";
    for (const ListedOutcome& o : k.not_judged)
      out += "not judged: " + o.listed.name() + " (" + file + ":" + std::to_string(o.listed.line) +
             "): " + o.now + "\n";
  }
  for (const ExpectedViolation& v : c.platform_not_run)
    out += "not judged: " + v.name() + " (" + file + ":" + std::to_string(v.line) +
           "): the run did not draw " + v.platform + "\n";
  if (fresh)
    out += "conformance: FAIL: " + plural(fresh, "violation", "violations") +
           (file.empty() ? " of the rasterization rules (no expectations file: each is new)"
                         : " not listed in " + file) +
           "\n";
  else
    out += "conformance: PASS: " +
           (all ? "every violation is listed in " + file : std::string("no violation")) + "\n";
  return out;
}

}  // namespace ra::analysis
