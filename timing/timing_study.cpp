// The rendering-time study (timing_study.h; Wimmer & Wonka 2003, sections 4.2, 5.2, 5.3, 7.2).
#include "timing/timing_study.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <stdexcept>

#include "scenes/scene_statistics.h"
#include "scenes/vertex_cache.h"
#include "stats/descriptive.h"
#include "util/atomic_file.h"
#include "util/counter_rng.h"
#include "util/errors.h"
#include "util/gl_child_process.h"

// What a platform's child process sends its parent (timing.json's raw measurements): the members
// under their own names.
namespace ra::timing {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ObjectSample, object, alpha, gamma, phi, triangles, vertices,
                                   transformed, pixels, state_changes, cpu_us, gpu_us)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FrameSample, frame, objects, cpu_us, gpu_us)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RendererInfo, platform, gallium_driver, backend, lp_num_threads,
                                   renderer, version, vendor, timer_query, timer_query_listed,
                                   timer_query_bits, depth_bits)
}  // namespace ra::timing

namespace ra::timing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Counter-based uniform numbers: the viewpoints of scene s are the same on every platform.
class Rng {
 public:
  Rng(uint64_t seed, uint64_t stream) : key_(splitmix64(splitmix64(seed) ^ (stream * 0x9E37u))) {}
  double uniform01() { return double(splitmix64(key_ + 0x632BE59BD9B4E019ull * ++n_) >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  int64_t integer(int64_t lo, int64_t hi) {
    return lo + int64_t(splitmix64(key_ + 0x632BE59BD9B4E019ull * ++n_) % uint64_t(hi - lo + 1));
  }

 private:
  uint64_t key_, n_ = 0;
};

// Throttled progress lines.
class Reporter {
 public:
  Reporter(const Progress& p, std::string prefix) : p_(p), prefix_(std::move(prefix)) {}
  void line(const std::string& what, bool force = false) {
    if (!p_) return;
    const auto now = Clock::now();
    if (!force && std::chrono::duration<double>(now - last_).count() < 2.0) return;
    last_ = now;
    p_(prefix_ + what);
  }

 private:
  const Progress& p_;
  std::string prefix_;
  Clock::time_point last_{};
};

struct ObjectStatic {
  int64_t triangles = 0, vertices = 0, transformed = 0;
};

// Times `objects` drawn alone (the clear not timed), `reps` times; pixels counted first.
void measure_object(SceneRenderer& r, int object, int reps, ObjectSample& s) {
  s.pixels = r.pixels_alone(object);
  std::vector<int64_t> binds;
  const std::vector<int> one{object};
  s.cpu_us.clear();
  s.gpu_us.clear();
  for (int k = 0; k < reps; ++k) {
    const DrawTime t = r.time_draw(one, false, k == 0 ? &binds : nullptr);
    s.cpu_us.push_back(t.cpu_us);
    if (r.measuring_gpu()) s.gpu_us.push_back(t.gpu_us);
  }
  s.state_changes = binds.empty() ? 0 : binds[0];
}

// 3. The camera path: every frame_stride-th frame drawn whole `repetitions` times, and the
// sample of each object in its view. Returns the objects the path sees.
std::set<int> measure_camera_path(SceneRenderer& r, const TimingSettings& settings,
                                  const WorkSettings& work, const scenes::Scene& scene,
                                  const std::vector<scenes::Viewpoint>& path,
                                  const std::vector<ObjectStatic>& stat, Reporter& rep,
                                  const std::string& tag, SceneMeasurements& sm) {
  const scenes::CameraSettings& cam = settings.camera;
  const geometry::Mat4 projection = scenes::projection_of(cam);
  std::set<int> seen;
  int measured_frames = 0;
  const int total_frames = (int(path.size()) + work.frame_stride - 1) / work.frame_stride;
  for (std::size_t f = 0; f < path.size(); f += std::size_t(work.frame_stride)) {
    const scenes::Viewpoint& vp = path[f];
    const geometry::Mat4 view = scenes::look_at(vp);
    const scenes::Frustum fr = scenes::frustum_of(projection * view);
    FrameSample fs;
    fs.frame = int(f);
    std::vector<int> visible;
    for (std::size_t o = 0; o < scene.objects.size(); ++o)
      if (fr.intersects(scene.objects[o].bounds)) visible.push_back(int(o));
    r.set_viewpoint(vp);
    std::vector<int64_t> binds;
    for (int k = 0; k < work.repetitions; ++k) {
      const DrawTime t = r.time_draw(visible, true, k == 0 ? &binds : nullptr);
      fs.cpu_us.push_back(t.cpu_us);
      if (r.measuring_gpu()) fs.gpu_us.push_back(t.gpu_us);
    }
    for (std::size_t i = 0; i < visible.size(); ++i) {
      const int o = visible[i];
      ObjectSample s;
      s.object = o;
      const scenes::BoundingSphere& b = scene.objects[std::size_t(o)].bounds;
      s.alpha = scenes::clipped_alpha(view, cam, b);
      scenes::view_direction_angles(vp.eye, b.centre, &s.gamma, &s.phi);
      s.triangles = stat[std::size_t(o)].triangles;
      s.vertices = stat[std::size_t(o)].vertices;
      s.transformed = stat[std::size_t(o)].transformed;
      s.pixels = r.pixels_alone(o);
      s.state_changes = binds.empty() ? 0 : binds[i];
      fs.objects.push_back(std::move(s));
      seen.insert(o);
    }
    sm.frames.push_back(std::move(fs));
    ++measured_frames;
    rep.line(tag + "path frames " + std::to_string(measured_frames) + "/" +
             std::to_string(total_frames));
  }
  return seen;
}

// 4. The per-object sampling tables of the objects the path sees (medians of pos_repetitions).
void measure_pos_tables(SceneRenderer& r, const TimingSettings& settings, const WorkSettings& work,
                        const scenes::Scene& scene, const std::set<int>& seen, Reporter& rep,
                        const std::string& tag, SceneMeasurements& sm) {
  const scenes::CameraSettings& cam = settings.camera;
  const double deg = M_PI / 180.0;
  int done = 0;
  for (int o : seen) {
    MeasuredPosTable mt;
    mt.object = o;
    mt.table = PosTable(settings.pos_grid, settings.pos_prune_alpha_deg * deg);
    const scenes::BoundingSphere& b = scene.objects[std::size_t(o)].bounds;
    for (const auto& p : mt.table.points_to_measure()) {
      const scenes::Viewpoint vp =
          scenes::viewpoint_for(b, cam, settings.pos_grid.alpha_at(p[0]),
                                settings.pos_grid.gamma_at(p[1]), settings.pos_grid.phi_at(p[2]));
      r.set_viewpoint(vp);
      std::vector<double> cpu;
      for (int k = 0; k < work.pos_repetitions; ++k) cpu.push_back(r.time_draw({o}, false).cpu_us);
      mt.table.set(p[0], p[1], p[2], stats::median(cpu));
    }
    sm.pos.push_back(std::move(mt));
    ++done;
    rep.line(tag + "pos tables " + std::to_string(done) + "/" + std::to_string(seen.size()));
  }
}

}  // namespace

PlatformMeasurements measure_platform(const TimingSettings& settings, const std::string& platform,
                                      const std::vector<scenes::Scene>& scenes,
                                      const std::vector<std::vector<scenes::Viewpoint>>& paths,
                                      const Progress& progress) {
  const auto t_start = Clock::now();
  const WorkSettings& work = settings.work_for(platform);
  PlatformMeasurements out;
  SceneRenderer r(platform, settings.camera, settings.gpu_timer);
  out.renderer = r.info();
  Reporter rep(progress, platform + ": ");
  rep.line(r.info().renderer + " (" + r.info().version + "), GL_TIME_ELAPSED " +
               (r.info().timer_query ? "supported" : "not supported"),
           true);
  const scenes::CameraSettings& cam = settings.camera;
  const geometry::Mat4 projection = scenes::projection_of(cam);
  const double deg = M_PI / 180.0;
  const double alpha_lo = settings.alpha_min_deg * deg, alpha_hi = scenes::max_clipped_alpha(cam);

  for (std::size_t si = 0; si < scenes.size(); ++si) {
    const auto t_scene = Clock::now();
    const scenes::Scene& scene = scenes[si];
    const std::vector<scenes::Viewpoint>& path = paths[si];
    SceneMeasurements sm;
    sm.name = settings.scenes[si].name;
    sm.kind = scene.kind;
    sm.path_frames = int(path.size());
    const std::string tag = sm.name + ": ";
    rep.line(tag + "uploading " + std::to_string(scene.objects.size()) + " objects", true);
    r.upload(scene);

    std::vector<ObjectStatic> stat(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const scenes::StripMesh& mesh = scene.objects[o].mesh;
      stat[o].triangles = int64_t(mesh.triangle_count());
      stat[o].vertices = int64_t(mesh.vertex_count());
      stat[o].transformed = scenes::transformed_vertices(mesh, settings.cache_size);
      sm.triangles += stat[o].triangles;
      sm.vertices += stat[o].vertices;
      sm.transformed += stat[o].transformed;
    }
    sm.objects = int64_t(scene.objects.size());
    sm.textures = int64_t(scene.textures.size());
    sm.state_switches = scenes::scene_texture_binds(scene);

    // 1. frame base: clear + glFinish
    {
      r.set_viewpoint(path.empty() ? scenes::Viewpoint{} : path.front());
      const int n = std::max(10, work.repetitions * 10);
      for (int k = 0; k < n; ++k) sm.frame_base_us.push_back(r.time_draw({}, true).cpu_us);
    }

    // 2. object measurements
    const int share = work.object_samples / int(scenes.size()) +
                      (int(si) < work.object_samples % int(scenes.size()) ? 1 : 0);
    Rng rng(settings.seed, si);
    for (int k = 0; k < share; ++k) {
      ObjectSample s;
      s.object = int(rng.integer(0, int64_t(scene.objects.size()) - 1));
      const scenes::BoundingSphere& b = scene.objects[std::size_t(s.object)].bounds;
      const double alpha = alpha_lo * std::pow(alpha_hi / alpha_lo, rng.uniform01());
      s.gamma = rng.uniform(0, 2 * M_PI);
      s.phi = rng.uniform(settings.phi_min_deg * deg, settings.phi_max_deg * deg);
      const scenes::Viewpoint vp = scenes::viewpoint_for(b, cam, alpha, s.gamma, s.phi);
      s.alpha = scenes::clipped_alpha(scenes::look_at(vp), cam, b);
      r.set_viewpoint(vp);
      s.triangles = stat[std::size_t(s.object)].triangles;
      s.vertices = stat[std::size_t(s.object)].vertices;
      s.transformed = stat[std::size_t(s.object)].transformed;
      measure_object(r, s.object, work.repetitions, s);
      sm.object_samples.push_back(std::move(s));
      rep.line(tag + "object measurements " + std::to_string(k + 1) + "/" + std::to_string(share));
    }

    // 3. camera path; 4. per-object sampling tables of the objects it sees
    const std::set<int> seen =
        measure_camera_path(r, settings, work, scene, path, stat, rep, tag, sm);
    measure_pos_tables(r, settings, work, scene, seen, rep, tag, sm);

    // the system task: one viewpoint of one scene's path (default: the first scene's middle one)
    const bool system_here = settings.system_task_scene.empty() ? si == 0
                                                                : sm.name == settings.system_task_scene;
    if (system_here && !path.empty()) {
      if (settings.system_task_frame >= int(path.size()))
        throw UserError(settings.file + ": timing.system_task_frame = " +
                        std::to_string(settings.system_task_frame) + " is out of range (allowed: 0 to " +
                        std::to_string(path.size() - 1) + ", the frames of scene " + sm.name + ")");
      const std::size_t f = settings.system_task_frame >= 0 ? std::size_t(settings.system_task_frame)
                                                            : path.size() / 2;
      const scenes::Frustum fr = scenes::frustum_of(projection * scenes::look_at(path[f]));
      std::vector<int> visible;
      for (std::size_t o = 0; o < scene.objects.size(); ++o)
        if (fr.intersects(scene.objects[o].bounds)) visible.push_back(int(o));
      r.set_viewpoint(path[f]);
      out.system_scene = sm.name;
      out.system_frame = int(f);
      out.system_visible_objects = int(visible.size());
      for (int k = 0; k < work.system_task_renders; ++k) {
        const DrawTime t = r.time_draw(visible, true);
        out.system_cpu_us.push_back(t.cpu_us);
        if (r.measuring_gpu()) out.system_gpu_us.push_back(t.gpu_us);
        rep.line(tag + "system task " + std::to_string(k + 1) + "/" +
                 std::to_string(work.system_task_renders));
      }
    }
    sm.seconds = seconds_since(t_scene);
    rep.line(tag + "done in " + std::to_string(int(std::lround(sm.seconds))) + " s", true);
    out.scenes.push_back(std::move(sm));
  }
  out.seconds = seconds_since(t_start);
  return out;
}

PlatformMeasurements measure_platform_in_child(
    const TimingSettings& settings, const std::string& platform,
    const std::vector<scenes::Scene>& scenes,
    const std::vector<std::vector<scenes::Viewpoint>>& paths, const std::string& scratch_dir,
    const Progress& progress) {
  auto failed = [&](const std::string& error) {
    PlatformMeasurements m;
    m.renderer.platform = platform;
    m.error = error;
    return m;
  };
  nlohmann::json j;
  try {
    j = run_in_child(scratch_dir, "timing-" + platform, [&] {
      return to_json(measure_platform(settings, platform, scenes, paths, progress));
    });
  } catch (const ChildProcessError& e) {
    return failed(e.what());
  }
  try {
    return platform_measurements_from_json(j);
  } catch (const std::exception& e) {
    return failed(std::string("the measuring process's result is unreadable (") + e.what() + ")");
  }
}

// ---- JSON of the measurements (child -> parent; samples and renderer: the macros above) ----

nlohmann::json to_json(const PlatformMeasurements& m) {
  nlohmann::json j;
  j["renderer"] = m.renderer;
  j["system_scene"] = m.system_scene;
  j["system_frame"] = m.system_frame;
  j["system_visible_objects"] = m.system_visible_objects;
  j["system_cpu_us"] = m.system_cpu_us;
  j["system_gpu_us"] = m.system_gpu_us;
  j["seconds"] = m.seconds;
  j["error"] = m.error;
  j["scenes"] = nlohmann::json::array();
  for (const SceneMeasurements& s : m.scenes) {
    nlohmann::json js = {{"name", s.name},          {"kind", s.kind},
                         {"objects", s.objects},    {"triangles", s.triangles},
                         {"vertices", s.vertices},  {"transformed", s.transformed},
                         {"textures", s.textures},  {"state_switches", s.state_switches},
                         {"path_frames", s.path_frames}, {"frame_base_us", s.frame_base_us},
                         {"seconds", s.seconds}};
    js["object_samples"] = s.object_samples;
    js["frames"] = s.frames;
    js["pos"] = nlohmann::json::array();
    for (const MeasuredPosTable& p : s.pos) {
      const PosGrid& g = p.table.grid();
      js["pos"].push_back({{"object", p.object},
                           {"grid", {g.n_alpha, g.n_gamma, g.n_phi}},
                           {"alpha", {g.alpha_min, g.alpha_max}},
                           {"phi", {g.phi_min, g.phi_max}},
                           {"prune_alpha", p.table.prune_alpha()},
                           {"us", p.table.values()}});
    }
    j["scenes"].push_back(std::move(js));
  }
  return j;
}

PlatformMeasurements platform_measurements_from_json(const nlohmann::json& j) {
  PlatformMeasurements m;
  m.renderer = j.at("renderer").get<RendererInfo>();
  m.system_scene = j.at("system_scene");
  m.system_frame = j.at("system_frame");
  m.system_visible_objects = j.at("system_visible_objects");
  m.system_cpu_us = j.at("system_cpu_us").get<std::vector<double>>();
  m.system_gpu_us = j.at("system_gpu_us").get<std::vector<double>>();
  m.seconds = j.at("seconds");
  m.error = j.at("error");
  for (const auto& js : j.at("scenes")) {
    SceneMeasurements s;
    s.name = js.at("name");
    s.kind = js.at("kind");
    s.objects = js.at("objects");
    s.triangles = js.at("triangles");
    s.vertices = js.at("vertices");
    s.transformed = js.at("transformed");
    s.textures = js.at("textures");
    s.state_switches = js.at("state_switches");
    s.path_frames = js.at("path_frames");
    s.frame_base_us = js.at("frame_base_us").get<std::vector<double>>();
    s.seconds = js.at("seconds");
    s.object_samples = js.at("object_samples").get<std::vector<ObjectSample>>();
    s.frames = js.at("frames").get<std::vector<FrameSample>>();
    for (const auto& jp : js.at("pos")) {
      PosGrid g;
      g.n_alpha = jp.at("grid")[0];
      g.n_gamma = jp.at("grid")[1];
      g.n_phi = jp.at("grid")[2];
      g.alpha_min = jp.at("alpha")[0];
      g.alpha_max = jp.at("alpha")[1];
      g.phi_min = jp.at("phi")[0];
      g.phi_max = jp.at("phi")[1];
      MeasuredPosTable p;
      p.object = jp.at("object");
      p.table = PosTable(g, jp.at("prune_alpha").get<double>());
      const auto us = jp.at("us").get<std::vector<double>>();
      for (int i = 0; i < g.n_alpha; ++i)
        for (int k = 0; k < g.n_gamma; ++k)
          for (int jj = 0; jj < g.n_phi; ++jj)
            p.table.set(i, k, jj, us.at((std::size_t(i) * g.n_gamma + k) * g.n_phi + jj));
      s.pos.push_back(std::move(p));
    }
    m.scenes.push_back(std::move(s));
  }
  return m;
}

// ---- estimation ----

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return kNaN;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= double(n), my /= double(n);
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx == 0 || syy == 0) return kNaN;
  return sxy / std::sqrt(sxx * syy);
}

namespace {

CpuGpuComparison compare(const std::vector<std::pair<double, double>>& cpu_gpu) {
  CpuGpuComparison c;
  std::vector<double> ratio, cpu, gpu;
  for (auto [a, b] : cpu_gpu) {
    if (!(a > 0) || !std::isfinite(b)) continue;
    ratio.push_back(b / a);
    cpu.push_back(a);
    gpu.push_back(b);
  }
  c.n = ratio.size();
  c.median_ratio = ratio.empty() ? kNaN : stats::median(ratio);
  c.pearson_r = pearson(cpu, gpu);
  return c;
}

}  // namespace

PlatformAnalysis analyse_platform(const TimingSettings& settings, const PlatformMeasurements& m) {
  PlatformAnalysis a;
  a.platform = m.renderer.platform;
  if (!m.system_cpu_us.empty()) a.system = system_task_stats(m.system_cpu_us, 0.99);
  a.gpu_measured = !m.system_gpu_us.empty();

  // the object measurements of every scene, pooled
  std::vector<ObjectCounts> x;
  std::vector<double> y;
  std::vector<std::pair<double, double>> obj_cpu_gpu, frame_cpu_gpu;
  for (const SceneMeasurements& s : m.scenes)
    for (const ObjectSample& o : s.object_samples) {
      x.push_back(counts_of(o));
      y.push_back(stats::median(o.cpu_us));
      obj_cpu_gpu.emplace_back(y.back(), stats::median_or_nan(o.gpu_us));
    }
  for (bool intercept : {false, true})
    for (Heuristic h : kAllHeuristics) a.fits.push_back(fit_heuristic(h, x, y, intercept));
  for (const HeuristicFit& f : a.fits)
    a.methods.push_back(std::string(heuristic_name(f.heuristic)) + (f.intercept ? "+b" : ""));
  a.methods.push_back("pos");

  for (const SceneMeasurements& s : m.scenes) {
    const double base = stats::median(s.frame_base_us);
    a.frame_base_us[s.name] = base;
    std::map<int, const PosTable*> pos;
    for (const MeasuredPosTable& p : s.pos) pos[p.object] = &p.table;
    std::vector<FramePrediction>& preds = a.frames[s.name];
    for (const FrameSample& f : s.frames) {
      FramePrediction p;
      p.frame = f.frame;
      p.visible = int(f.objects.size());
      p.measured_us = stats::median(f.cpu_us);
      p.measured_gpu_us = stats::median_or_nan(f.gpu_us);
      frame_cpu_gpu.emplace_back(p.measured_us, p.measured_gpu_us);
      for (std::size_t k = 0; k < a.fits.size(); ++k) {
        double sum = base;
        for (const ObjectSample& o : f.objects) sum += a.fits[k].predict(counts_of(o));
        p.predicted_us[a.methods[k]] = sum;
      }
      double sum = base;
      // (alpha 0: kept by the sphere test, yet its cone misses the window; it is still drawn
      // and clipped, and the lookup clamps it to the table's smallest alpha)
      for (const ObjectSample& o : f.objects)
        sum += pos.at(o.object)->lookup(o.alpha, o.gamma, o.phi, settings.pos_lookup);
      p.predicted_us["pos"] = sum;
      preds.push_back(std::move(p));
    }
    if (preds.empty()) continue;
    std::vector<double> measured;
    for (const FramePrediction& p : preds) measured.push_back(p.measured_us);
    for (const std::string& method : a.methods) {
      std::vector<double> predicted;
      for (const FramePrediction& p : preds) predicted.push_back(p.predicted_us.at(method));
      a.table6_ms2[s.name][method] = average_squared_error_ms2(predicted, measured);
    }
  }
  if (a.gpu_measured) {
    a.cpu_gpu_objects = compare(obj_cpu_gpu);
    a.cpu_gpu_frames = compare(frame_cpu_gpu);
  }
  return a;
}

}  // namespace ra::timing
