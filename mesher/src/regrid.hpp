// Private: quads for a cavity of the re-fill read by its topology alone (docs/mesher.md,
// "Regrid"): how many of the cavity's quads meet each node of its boundary cycle says how the
// boundary turns, and where it turns as a rectangle's (or a triangle's, a pentagon's) does, a
// structured grid with no irregular node inside (or one) fits it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks::mesher_detail {

/// Quads over a cavity's local ids (its cycle 0..n-1, then the inner nodes n..) and the inner
/// nodes' positions. Quads run the way the cycle does (counter-clockwise for a cavity).
struct TurnFill {
  std::vector<Vec2> interior;
  std::vector<std::array<std::uint32_t, 4>> quads;
};

/// turn[i] = 2 - (the quads of the fill meeting cycle node i): 1 a corner, 0 straight, -1 a
/// reflex corner. The cycle walked on the integer lattice (left at 1, on at 0, right at -1):
/// when the walk closes without meeting itself it bounds a set of lattice squares (a
/// polyomino), which are the fill; every inner node is in four of them. None otherwise (the
/// turns must add up to 4; a walk that does not close has a dislocation inside: no grid
/// without an irregular node fits). Inner positions are left at zero (place_harmonic).
std::optional<TurnFill> lattice_fill(const std::vector<int>& turn);

/// A cycle of c = 3 or 5 corners (turn 1) and straight nodes (turn 0): c grids round one centre
/// node of c quads, grid i at corner i. With s_j the edges of side j (corner j to j + 1) and
/// L_j the edges of the spoke from the centre to side j, grid i is L_{i-1} x L_i and
/// s_j = L_{j-1} + L_{j+1}, which for odd c has one solution: the fill exists when it is whole
/// and every L_j >= 1. Inner positions are left at zero (place_harmonic).
std::optional<TurnFill> sided_fill(const std::vector<int>& turn);

/// A cycle of n nodes all straight (turn 0; n even, at least 8): an O-grid. `layers` rings of
/// n quads inside the cycle, then a core grid of a x b quads (a = n / 4, b = n / 2 - a) whose
/// four corners are its only irregular nodes (three quads each), the first corner on the ring
/// under cycle node `start`. Inner positions are left at zero (place_harmonic).
std::optional<TurnFill> ogrid_fill(const std::vector<int>& turn,
                                   std::uint32_t layers,
                                   std::uint32_t start);

/// Every inner node at the mean of its neighbours along quad edges, `sweeps` Gauss-Seidel
/// sweeps from the cycle's centroid (a discrete harmonic map onto the cycle's polygon).
void place_harmonic(TurnFill& fill, const std::vector<Vec2>& cycle, int sweeps);

}  // namespace laytracks::mesher_detail
