// Plans along a camera path and their rendering (plan_rendering.h).
#include "regulation/plan_rendering.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/gl_child_process.h"
#include "timing/scene_renderer.h"
#include "timing/time_heuristics.h"
#include "scenes/camera.h"
#include "stats/descriptive.h"

namespace ra::regulation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using Clock = std::chrono::steady_clock;

std::vector<int> frames_of(const std::vector<scenes::Viewpoint>& path, int stride) {
  std::vector<int> f;
  for (int i = 0; i < int(path.size()); i += stride) f.push_back(i);
  return f;
}

// All frames x budgets x policies planned with `base_us` taken off each budget; `pixels`
// (optional): measured #pix per planned frame (in frames_of order).
std::vector<FrameRecord> plan_all(const std::vector<LodChain>& chains,
                                  const std::vector<double>& weights,
                                  const std::vector<scenes::Viewpoint>& path,
                                  const RegulationSettings& s, double base_us,
                                  const std::vector<int>& level_offset,
                                  const std::vector<FramePixels>* pixels = nullptr) {
  std::vector<FrameRecord> out;
  const std::vector<int> frames = frames_of(path, s.frame_stride);
  for (std::size_t slot = 0; slot < frames.size(); ++slot) {
    const int f = frames[slot];
    for (double b_ms : s.budgets_ms) {
      std::vector<FrameObject> objs;
      const Instance inst = frame_instance(chains, weights, path[f], s, b_ms * 1000.0 - base_us, &objs,
                                           pixels ? &(*pixels)[slot] : nullptr);
      const bool feasible = base_plan(inst).fits;
      Plan opt;
      bool have_opt = true;
      try {
        opt = optimal_plan(inst, s.dp_max_cells);
      } catch (const std::length_error&) {
        have_opt = false;
      }
      for (Policy p : kAllPolicies) {
        FrameRecord r;
        r.frame = f;
        r.budget_ms = b_ms;
        r.policy = policy_name(p);
        r.visible = int(objs.size());
        r.budget_units = inst.budget;
        Plan plan;
        if (p == Policy::kOptimal) {
          if (!have_opt) continue;  // too large for the exact DP: not reported
          plan = opt;
        } else {
          plan = plan_with(p, inst);
        }
        r.plan_units = plan.cost;
        r.expected_cost = plan.loss;
        r.value = plan.value;
        r.fits = plan.fits;
        r.feasible = feasible;
        r.value_ratio_to_optimal = !have_opt ? kNaN
                                   : plan.value > 0 ? opt.value / plan.value
                                   : (opt.value > 0 ? std::numeric_limits<double>::infinity() : 1.0);
        r.predicted_us = base_us;
        r.predicted_estimated_us = base_us;
        for (std::size_t j = 0; j < objs.size(); ++j) {
          const int k = plan.choice[j];
          r.predicted_us += objs[j].predicted_us[k];
          r.predicted_estimated_us += objs[j].predicted_estimated_us[k];
          r.pixels += objs[j].pixels[k];
          r.triangles += chains[objs[j].object].levels[k].triangles;
          r.transformed += chains[objs[j].object].levels[k].transformed;
          r.draw.push_back(level_offset[objs[j].object] + k);
        }
        r.measured_median_us = kNaN;
        out.push_back(std::move(r));
      }
    }
  }
  return out;
}

nlohmann::json record_json(const FrameRecord& r) {
  return {{"measured_us", r.measured_us}};
}

}  // namespace

std::vector<int> visible_chains(const std::vector<LodChain>& chains, const scenes::Viewpoint& vp,
                                const scenes::CameraSettings& cam) {
  const geometry::Mat4 view = scenes::look_at(vp);
  const scenes::Frustum frustum = scenes::frustum_of(scenes::projection_of(cam) * view);
  std::vector<int> v;
  for (int j = 0; j < int(chains.size()); ++j)
    if (footprint_of(chains[j].bounds, view, frustum, cam).visible) v.push_back(j);
  return v;
}

Instance frame_instance(const std::vector<LodChain>& chains, const std::vector<double>& weights,
                        const scenes::Viewpoint& vp, const RegulationSettings& s, double budget_us,
                        std::vector<FrameObject>* objects, const FramePixels* measured) {
  const geometry::Mat4 view = scenes::look_at(vp);
  const scenes::Frustum frustum = scenes::frustum_of(scenes::projection_of(s.camera) * view);
  Instance inst;
  objects->clear();
  for (int j = 0; j < int(chains.size()); ++j) {
    const LodChain& c = chains[j];
    FrameObject fo;
    fo.object = j;
    fo.footprint = footprint_of(c.bounds, view, frustum, s.camera);
    if (!fo.footprint.visible) continue;
    fo.weight = weights[j];
    Item item;
    item.distance = fo.footprint.distance_m;
    const std::vector<double>* mp =
        measured && j < int(measured->size()) && (*measured)[j].size() == c.levels.size() ? &(*measured)[j]
                                                                                         : nullptr;
    fo.pixels_measured = mp != nullptr;
    for (std::size_t k = 0; k < c.levels.size(); ++k) {
      const LodLevel& l = c.levels[k];
      const double pix = mp ? (*mp)[k] : fo.footprint.pixels;
      const double us = predict_us(s.cost, double(l.transformed), pix);
      fo.pixels.push_back(pix);
      fo.predicted_estimated_us.push_back(predict_us(s.cost, double(l.transformed), fo.footprint.pixels));
      const double cp = perceptual_cost(fo.footprint.area_fraction, l.error_m, fo.footprint.distance_m,
                                        fo.footprint.focal_px, s.error_exponent);
      fo.predicted_us.push_back(us);
      fo.perceptual.push_back(cp);
      item.options.push_back({cost_units(s.cost, us), fo.weight * cp});
    }
    inst.items.push_back(std::move(item));
    objects->push_back(std::move(fo));
  }
  // budget_us may be negative (the empty frame alone exceeds it): no plan fits then
  inst.budget = budget_us <= 0 ? -1 : int64_t(std::floor(budget_us / s.cost.cost_unit_us));
  return inst;
}

RenderOutcome plan_and_render(const scenes::Scene& scene, const std::vector<LodChain>& chains,
                              const std::vector<double>& weights,
                              const std::vector<scenes::Viewpoint>& path,
                              const RegulationSettings& s, const std::string& scratch_dir,
                              bool progress) {
  const auto t0 = Clock::now();
  std::vector<int> level_offset;
  int n = 0;
  for (const LodChain& c : chains) {
    level_offset.push_back(n);
    n += int(c.levels.size());
  }
  RenderOutcome out;
  if (!s.render) {
    out.records = plan_all(chains, weights, path, s, 0.0, level_offset);
    out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
  }
  // The scene the renderer draws: every level of every object, object index offset + level.
  scenes::Scene lod;
  lod.kind = scene.kind;
  lod.textures = scene.textures;
  lod.layout = scene.layout;
  for (const LodChain& c : chains)
    for (std::size_t k = 0; k < c.levels.size(); ++k)
      lod.objects.push_back({c.name + " L" + std::to_string(k), c.levels[k].mesh, c.bounds});

  nlohmann::json measured;
  try {
    measured = run_in_child(scratch_dir, "regulation-render", [&] {
      nlohmann::json j;
      timing::SceneRenderer r(s.platform, s.camera, /*gpu_timer=*/false);
      r.upload(lod);
      std::vector<int> all(lod.objects.size());
      for (int i = 0; i < int(all.size()); ++i) all[i] = i;
      r.set_viewpoint(path.front());
      r.time_draw(all, true);  // warm-up: first use of every buffer and texture, untimed
      std::vector<double> base;
      for (int i = 0; i < std::max(20, s.repetitions); ++i) base.push_back(r.time_draw({}, true).cpu_us);
      const double base_us = stats::median(base);
      // #pix of every level of every visible object of every planned frame (untimed)
      std::vector<FramePixels> pixels;
      if (s.cost.measured_pixels) {
        for (int f : frames_of(path, s.frame_stride)) {
          r.set_viewpoint(path[f]);
          FramePixels fp(chains.size());
          for (int c : visible_chains(chains, path[f], s.camera))
            for (std::size_t k = 0; k < chains[c].levels.size(); ++k)
              fp[c].push_back(double(r.pixels_alone(level_offset[c] + int(k))));
          pixels.push_back(std::move(fp));
        }
        j["pixels"] = pixels;
      }
      std::vector<FrameRecord> recs =
          plan_all(chains, weights, path, s, base_us, level_offset, s.cost.measured_pixels ? &pixels : nullptr);
      std::size_t i = 0, done_frames = 0, total_frames = frames_of(path, s.frame_stride).size();
      auto last = Clock::now();
      while (i < recs.size()) {  // records of one frame are contiguous
        std::size_t e = i;
        while (e < recs.size() && recs[e].frame == recs[i].frame) ++e;
        r.set_viewpoint(path[recs[i].frame]);
        for (int rep = 0; rep < s.repetitions; ++rep)
          for (std::size_t k = i; k < e; ++k)  // interleaved: drift hits every policy alike
            recs[k].measured_us.push_back(r.time_draw(recs[k].draw, true).cpu_us);
        i = e;
        ++done_frames;
        if (progress && std::chrono::duration<double>(Clock::now() - last).count() > 2) {
          last = Clock::now();
          std::fprintf(stderr, "regulation: rendered %zu / %zu frames\n", done_frames, total_frames);
        }
      }
      j["renderer"] = r.info().renderer;
      j["version"] = r.info().version;
      j["base_us"] = base_us;
      j["base_reps_us"] = base;
      j["records"] = nlohmann::json::array();
      for (const FrameRecord& fr : recs) j["records"].push_back(record_json(fr));
      return j;
    });
  } catch (const ChildProcessError& e) {
    out.error = e.what();
  }
  if (out.error.empty()) {
    try {
      out.renderer = measured.value("renderer", "");
      out.version = measured.value("version", "");
      out.base_us = measured["base_us"].get<double>();
      out.base_reps_us = measured["base_reps_us"].get<std::vector<double>>();
      // the planning is deterministic: redo it here with the child's base and pixels, attach
      // the times
      std::vector<FramePixels> pixels;
      if (measured.contains("pixels")) {
        pixels = measured["pixels"].get<std::vector<FramePixels>>();
        out.pixels_measured = true;
        const std::vector<int> frames = frames_of(path, s.frame_stride);
        if (pixels.size() != frames.size()) throw std::runtime_error("pixel frame count differs");
        for (std::size_t slot = 0; slot < frames.size(); ++slot) {
          const scenes::Viewpoint& vp = path[frames[slot]];
          const geometry::Mat4 view = scenes::look_at(vp);
          const scenes::Frustum frustum =
              scenes::frustum_of(scenes::projection_of(s.camera) * view);
          for (int c = 0; c < int(pixels[slot].size()); ++c) {
            if (pixels[slot][c].empty()) continue;
            PixelSample ps;
            ps.frame = frames[slot];
            ps.object = c;
            const Footprint fo = footprint_of(chains[c].bounds, view, frustum, s.camera);
            ps.distance_m = fo.distance_m;
            ps.radius_m = chains[c].bounds.radius;
            ps.estimated = fo.pixels;
            ps.measured = pixels[slot][c];
            out.pixels.push_back(std::move(ps));
          }
        }
      }
      out.records = plan_all(chains, weights, path, s, out.base_us, level_offset,
                             out.pixels_measured ? &pixels : nullptr);
      const auto& rs = measured["records"];
      if (rs.size() != out.records.size()) throw std::runtime_error("record count differs");
      for (std::size_t i = 0; i < out.records.size(); ++i) {
        FrameRecord& fr = out.records[i];
        fr.measured_us = rs[i]["measured_us"].get<std::vector<double>>();
        fr.measured_median_us = stats::median(fr.measured_us);
        fr.skipped = fr.measured_median_us > fr.budget_ms * 1000.0;
      }
    } catch (const std::exception& e) {
      out.error = std::string("the measuring process's result is unreadable (") + e.what() + ")";
    }
  }
  if (!out.error.empty()) {
    out.pixels_measured = false;
    out.pixels.clear();
    out.records = plan_all(chains, weights, path, s, 0.0, level_offset);
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

}  // namespace ra::regulation
