// Attention and expected perceptual cost (Horvitz & Lengyel 1997, sections 5.2, 5.3 and 7.2).
//
// The paper's equations, as we read them from the (garbled) text; CP(R_k, S_i) is the perceptual
// cost of drawing element S_i with rendering action R_k (perceptual_cost.h), E the evidence:
//   (1) CP = sum_i CP(R_k, S_i)                                       costs add over elements
//   (3) ECP = sum_i integral_0^1 p(A_Si = x | E) a(x) CP(R_k, S_i) dx continuous attention x in
//       [0, 1] and an attenuation a(x) in [0, 1] (no attention .. full attention)
//   (4) ECP = sum_i [p(A_Si | E) + (1 - p(A_Si | E)) alpha] CP(R_k, S_i)   binary attention: the
//       full cost when attended, alpha times it when not (alpha a constant in [0, 1])
//   (5) ECP = sum_i p(A_Si | E) CP(R_k, S_i)                          (4) with alpha = 0
//   (6) ECP = sum_j sum_i [p(A_Sij | A_Oj, E) p(A_Oj | E)
//             + (1 - p(A_Sij | A_Oj, E) p(A_Oj | E)) alpha] CP(R_k, S_ij)
//       attention to element i of a contiguous object j: attending the object, then the element
//   (7) ECP = sum_j sum_i p(A_Sij | A_Oj, E) p(A_Oj | E) CP(R_k, S_ij)  (6) with alpha = 0
// Equation (4) is (3) with the two-point distribution {0: 1 - p, 1: p} and a(0) = alpha, a(1) = 1;
// (6) is (4) with p = p(A_Sij | A_Oj) p(A_Oj).
//
// Section 7.2: objects were "tagged by hand ... as being in the group of primary actors, secondary
// actors, critical environment, and background environment" and equation (4) was used "for several
// values of alpha". Here an object's category gives its p(A_O | E); each object is one element
// (p(A_S | A_O) = 1 by default: a level of detail degrades the whole object), so the study's weight
// per object is equation (6) with that conditional. Objects are tagged by declaration (their name)
// or, otherwise, deterministically from the seed with the configured shares.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ra::regulation {

enum class Category { kPrimaryActor, kSecondaryActor, kCriticalEnvironment, kBackground };
constexpr int kCategories = 4;
const char* category_name(Category c);  // "primary_actor", "secondary_actor", "critical_environment", "background"
bool parse_category(const std::string& name, Category* out);

struct AttentionModel {
  // p(A_O | E): probability that a viewer attends to an object of each category (index: Category)
  std::array<double, kCategories> probability{0.9, 0.5, 0.25, 0.05};
  // shares of the objects the seeded tagger puts in each category; sum 1
  std::array<double, kCategories> share{0.05, 0.15, 0.30, 0.50};
  double alpha = 0.2;                 // attenuation of the cost of unattended objects, [0, 1]
  double element_given_object = 1.0;  // p(A_S | A_O, E): one element per object
  std::map<std::string, Category> tags;  // declared categories by object name (override the seed)
};

// Equation (4)'s weight of one element: p + (1 - p) alpha.
double binary_attention_weight(double p_attend, double alpha);
// Equation (6)'s weight: q = p(A_S | A_O) p(A_O); q + (1 - q) alpha. Equation (7): alpha = 0.
double object_attention_weight(double p_element_given_object, double p_object, double alpha);
// Equation (3)'s weight: integral_0^1 density(x) a(x) dx by the trapezoid rule on `steps`
// intervals (density need not be normalised: the integral is divided by integral density).
double continuous_attention_weight(const std::function<double(double)>& density,
                                   const std::function<double(double)>& attenuation,
                                   int steps = 1000);

// The weight of an object of category c under `model` (equation 6).
double attention_weight(const AttentionModel& model, Category c);

// Expected perceptual cost (equations 1 and 4-7): sum_i weight_i * cp_i.
double expected_perceptual_cost(const std::vector<double>& cp, const std::vector<double>& weight);

// Categories of objects named `names`: a declared tag, else a seeded draw u in [0, 1) against the
// cumulative shares (the same seed and names give the same tags).
std::vector<Category> tag_objects(const std::vector<std::string>& names, const AttentionModel& model,
                                  uint64_t seed);

}  // namespace ra::regulation
