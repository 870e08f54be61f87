// Where a cheaper level of kneiphof_klein_area (Kneiphof & Klein 2024 Sec. 4: binomial glints
// under a rectangular area light, p = D_Ωh/D_H with D_Ωh from the LTC polygon integral, Eq. 12–19)
// is indistinguishable from the exact count: the binomial family's levels (smooth, realtime,
// small_count, exact: the model's `binomial` parameter; smooth = L_o/L_i, the count's factor
// b/(N_P p) = 1), measured per cell of the binomial family's grid with its cone light replaced by
// a square one, decided by the same rule (compare_to_exact) with the table's one Šidák z.
//
// The light, declared before measuring: a square of side w at distance d = 1 along ω_o (the
// model's rectangle is centred along the query's ω_o, facing the shading point, not turned nor
// tilted), w chosen so that its solid angle equals the cone's of the grid's half-angle γ,
// 2π(1 − cos γ): the square subtends 4 asin(w²/(w² + 4d²)) (the solid angle of a w × w rectangle
// seen from a point on its axis at distance d), so w = 2d √(s/(1 − s)), s = sin(π(1 − cos γ)/2).
// Half-angles: 0.26° (kneiphof_klein's cap for a delta light, Sec. 5), 1° and 10° (quick; full
// adds 3°). The rest of the grid is the binomial family's (grid_axes): footprint N_P, roughness,
// incidence, the half-vector tilted sideways.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "verify/adequacy/binomial_adequacy.h"

namespace glintlab::verify::adequacy {

inline constexpr std::array<std::string_view, 1> kAreaFamilyModels = {"kneiphof_klein_area"};

// The light's distance (the model's default) and the side of the square whose solid angle is the
// cone's of half-angle `half_angle_deg`; the solid angle of a square of side w facing a point at
// distance d on its axis.
inline constexpr double kAreaLightDistance = 1.0;
double square_light_side(double half_angle_deg, double distance = kAreaLightDistance);
double square_solid_angle(double side, double distance = kAreaLightDistance);

// The grid: the binomial family's footprints, roughness, incidence, half-vector angles and
// positions per cell, with the square lights of the half-angles above (cells in make_grid's order,
// `light_half_angle_deg` the cone-equivalent half-angle of the square).
GridAxes area_grid_axes(Budget b);

// The model's parameter values (its kParams order) for a counting level of an area cell.
std::vector<double> area_level_param_values(const Cell& cell, BinomialLevel level,
                                            std::uint64_t seed);
// The pixel values of one level at `samples` surface positions (surface_position, cell_query);
// the smooth level is the model's smooth value L_o/L_i (LTC, evaluated at every position: what a
// shader without glints pays). Returns the loop's ns per evaluation.
double area_level_values(const Cell& cell, BinomialLevel level, int samples, std::uint64_t seed,
                         std::vector<double>& out);
// The clamped p and the smooth value L_o/L_i of an area cell.
std::pair<double, double> area_cell_probability_and_smooth(const Cell& cell);
// The engine chooser's level for an area cell at threshold tau (core/glints/area_chooser.h, on the
// model's parameters of the cell and its query at the centre position; N_P and p are the cell's):
// the table's `chooser` column of the area rows.
int area_cell_chooser(const Cell& cell, double tau);

// Every cell (measure_cell: the levels through level_values, which hands area cells to
// area_level_values), in parallel, each seeded by its position in the whole area grid under its
// own name ("adequacy.area"); the order and every value but ns_per_eval do not depend on the
// thread count.
inline constexpr const char* kAreaSeedName = "adequacy.area";
std::vector<CellResult> measure_area_grid_at(const std::vector<Cell>& cells,
                                             const std::vector<std::size_t>& positions,
                                             int samples, const Decision& d,
                                             const std::function<void()>& progress = {});

}  // namespace glintlab::verify::adequacy
