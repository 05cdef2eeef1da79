// Attention and expected perceptual cost (attention.h; Horvitz & Lengyel 1997, equations 3-7).
#include "regulation/attention.h"

#include <stdexcept>

#include "util/counter_rng.h"

namespace ra::regulation {

const char* category_name(Category c) {
  switch (c) {
    case Category::kPrimaryActor: return "primary_actor";
    case Category::kSecondaryActor: return "secondary_actor";
    case Category::kCriticalEnvironment: return "critical_environment";
    case Category::kBackground: return "background";
  }
  return "?";
}

bool parse_category(const std::string& name, Category* out) {
  for (int i = 0; i < kCategories; ++i)
    if (name == category_name(Category(i))) {
      *out = Category(i);
      return true;
    }
  return false;
}

double binary_attention_weight(double p, double alpha) { return p + (1 - p) * alpha; }

double object_attention_weight(double p_element_given_object, double p_object, double alpha) {
  return binary_attention_weight(p_element_given_object * p_object, alpha);
}

double continuous_attention_weight(const std::function<double(double)>& density,
                                   const std::function<double(double)>& attenuation, int steps) {
  if (steps < 1) throw std::invalid_argument("continuous_attention_weight: steps < 1");
  double num = 0, den = 0;
  for (int i = 0; i <= steps; ++i) {
    const double x = double(i) / steps;
    const double w = (i == 0 || i == steps) ? 0.5 : 1.0;
    num += w * density(x) * attenuation(x);
    den += w * density(x);
  }
  if (!(den > 0)) throw std::invalid_argument("continuous_attention_weight: density integrates to 0");
  return num / den;
}

double attention_weight(const AttentionModel& model, Category c) {
  return object_attention_weight(model.element_given_object, model.probability[int(c)], model.alpha);
}

double expected_perceptual_cost(const std::vector<double>& cp, const std::vector<double>& weight) {
  if (cp.size() != weight.size()) throw std::invalid_argument("expected_perceptual_cost: sizes differ");
  double s = 0;
  for (std::size_t i = 0; i < cp.size(); ++i) s += weight[i] * cp[i];
  return s;
}

std::vector<Category> tag_objects(const std::vector<std::string>& names, const AttentionModel& model,
                                  uint64_t seed) {
  std::vector<Category> out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    auto it = model.tags.find(names[i]);
    if (it != model.tags.end()) {
      out.push_back(it->second);
      continue;
    }
    util::CounterRng rng(seed, 0xA77E47ull, i);
    const double u = rng.uniform01();
    double cum = 0;
    Category c = Category::kBackground;
    for (int k = 0; k < kCategories; ++k) {
      cum += model.share[k];
      if (u < cum) {
        c = Category(k);
        break;
      }
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace ra::regulation
