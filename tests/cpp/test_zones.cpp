// Several contact zones (cpp/src/zones.cpp) against the single-contact
// solvers (one zone is the asymmetric solver's contact; far-apart punches are
// independent punches), the energy balance, symmetry and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/contact.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/profile.hpp"
#include "movingpunch/zones.hpp"

namespace mp = movingpunch;

namespace {

mp::ZonesParams layer(double vstar, double kw, double damping) {
  mp::ZonesParams p;
  p.layer.vstar = vstar;
  p.layer.kw = kw;
  p.layer.damping = damping;
  p.layer.tol = 1e-10;
  return p;
}

mp::ZonePunch cylinder(double load, double at) {
  mp::ZonePunch k;
  k.radius = 100.0;
  k.load = load;
  k.at = at;
  return k;
}

// The asymmetric solver's single contact the zones are compared with:
// V* = 0.5, kw h/mu = 1, damping 0.3 (R/h = 100, P/(mu h) = 0.002, tol 1e-11).
mp::AsymmetricSolution damped_reference() {
  mp::AsymmetricParams d;
  d.vstar = 0.5;
  d.kw = 1.0;
  d.damping = 0.3;
  d.tol = 1e-11;
  return mp::solve_asymmetric(d);
}

}  // namespace

TEST(Zones, OneZoneIsTheAsymmetricSolversContact) {
  const mp::AsymmetricSolution ref = damped_reference();
  mp::ZonesParams p = layer(0.5, 1.0, 0.3);
  p.punches = {cylinder(0.002, 0.0)};
  p.zones = {{0, ref.left() * 0.9, ref.right() * 1.1}};
  const mp::ZonesSolution z = mp::solve_zones(p);
  ASSERT_EQ(z.zones.size(), 1U);
  EXPECT_NEAR(z.zones[0].left, ref.left(), 1e-9);
  EXPECT_NEAR(z.zones[0].right, ref.right(), 1e-9);
  EXPECT_NEAR(z.drag[0], ref.drag(), 1e-9 * std::fabs(ref.drag()));
  // The energy balance: the dashpots take the drag's power.
  EXPECT_NEAR(mp::zones_dissipation(z), z.drag_total, 1e-7 * z.drag_total);
  EXPECT_NEAR(z.zones[0].load, 0.002, 1e-14);
}

TEST(Zones, OneRoundedFlatZoneIsTheAsymmetricSolversContact) {
  // The kinked slope (a rounded flat's face ends inside the zone):
  // collocated by its projection, the series extended by the half-plane
  // tail (docs/theory.md section 15.2), as the asymmetric solver's profile.
  mp::AsymmetricParams d;
  d.vstar = 0.2;
  d.kw = 1.0;
  d.damping = 0.3;
  d.tol = 1e-11;
  d.profile = mp::ProfileKind::rounded_flat;
  d.half_width = 0.3;
  d.radius = 100.0;
  const mp::AsymmetricSolution ref = mp::solve_asymmetric(d);
  mp::ZonesParams p = layer(0.2, 1.0, 0.3);
  mp::ZonePunch k = cylinder(0.002, 0.0);
  k.profile = mp::ProfileKind::rounded_flat;
  k.half_width = 0.3;
  p.punches = {k};
  p.zones = {{0, ref.left() * 0.9, ref.right() * 1.1}};
  const mp::ZonesSolution z = mp::solve_zones(p);
  ASSERT_EQ(z.zones.size(), 1U);
  EXPECT_TRUE(z.warnings.empty());
  EXPECT_NEAR(z.zones[0].left, ref.left(), 1e-9);
  EXPECT_NEAR(z.zones[0].right, ref.right(), 1e-9);
  EXPECT_NEAR(z.drag[0], ref.drag(), 1e-9 * std::fabs(ref.drag()));
  EXPECT_NEAR(mp::zones_dissipation(z), z.drag_total, 1e-7 * z.drag_total);
  // The collocated head and the tail: 4096 terms, whose coefficients
  // beyond the head are the half-plane's (b_m = d_{m+1}/(phi1 P)).
  const mp::ZoneResult& zr = z.zones[0];
  EXPECT_EQ(zr.b.size(), 4096);
  EXPECT_LT(zr.head, 64);
  const mp::PunchProfile prof = k.punch();
  const std::vector<double> dm = prof.slope_chebyshev_at(zr.offset, zr.half, 4097);
  for (int m : {zr.head, 1000, 4095})
    EXPECT_NEAR(zr.b(m), dm[static_cast<std::size_t>(m + 1)] / (z.phi1 * zr.load),
                1e-14 * std::fabs(zr.b(0)));
  // The whole series' pressure at the zone's centre agrees with the
  // asymmetric solver's (both heads converged, both tails the half-plane's).
  const mp::AsymmetricSolution one = zr.solution();
  EXPECT_NEAR(one.pressure(0.0), ref.pressure(0.0), 1e-8 * ref.pressure(0.0));
  EXPECT_NEAR(z.max_pressure, ref.max_pressure(), 1e-8 * ref.max_pressure());
}

TEST(Zones, FarApartPunchesAreSinglePunches) {
  mp::ContactParams c;
  c.vstar = 0.3;
  c.kw = 10.0;
  c.tol = 1e-12;
  const mp::SymmetricSolution single = mp::solve_contact(c);
  mp::ZonesParams p = layer(0.3, 10.0, 0.0);
  p.punches = {cylinder(0.002, -50.0), cylinder(0.002, 50.0)};
  p.zones = {{0, -51.0, -49.0}, {1, 49.0, 51.0}};
  const mp::ZonesSolution z = mp::solve_zones(p);
  ASSERT_EQ(z.zones.size(), 2U);
  EXPECT_NEAR(z.zones[0].left, -50.0 - single.a(), 1e-9);
  EXPECT_NEAR(z.zones[1].right, 50.0 + single.a(), 1e-9);
  EXPECT_GT(z.min_gap, 0.0);
}

TEST(Zones, SeparatedContactIsSymmetricAndComplementary) {
  const double v = 0.99 * mp::critical_vstar(0.1, 0.2);
  mp::ZonesParams p = layer(v, 0.1, 0.0);
  p.punches = {cylinder(0.002, 0.0)};
  p.zones = {{0, -1.8, -0.5}, {0, 0.5, 1.8}};
  const mp::ZonesSolution z = mp::solve_zones(p);
  ASSERT_EQ(z.zones.size(), 2U);
  EXPECT_NEAR(z.zones[0].left, -z.zones[1].right, 1e-11);
  EXPECT_NEAR(z.zones[0].right, -z.zones[1].left, 1e-11);
  EXPECT_NEAR(z.zones[0].load, 0.001, 1e-13);
  EXPECT_GT(z.zones[0].margin, 0.0);  // p >= 0 with square-root ends
  EXPECT_GT(z.min_gap, -1e-6 * z.gap_scale);
  EXPECT_LT(z.residual, 1e-10);
  EXPECT_LT(z.error_estimate, 1e-8);
}

TEST(Zones, BadInputIsRefused) {
  mp::ZonesParams p = layer(0.5, 1.0, 0.0);
  p.punches = {cylinder(0.002, 0.0)};
  p.zones = {{0, -0.5, 0.5}, {0, 0.4, 0.8}};  // overlapping
  EXPECT_THROW(mp::solve_zones(p), mp::InvalidParameter);
  p.zones = {{0, -0.5, 0.5}};
  p.layer.friction = 0.2;
  EXPECT_THROW(mp::solve_zones(p), mp::InvalidParameter);
  p.layer.friction = 0.0;
  p.punches[0].load = -1.0;
  EXPECT_THROW(mp::solve_zones(p), mp::InvalidParameter);
  p.punches[0].load = 0.002;
  p.zones = {{1, -0.5, 0.5}};  // no such punch
  EXPECT_THROW(mp::solve_zones(p), mp::InvalidParameter);
  p.zones = {{0, -0.5, 0.5}};
  p.layer.vstar = mp::critical_vstar(1.0, 0.2);
  EXPECT_THROW(mp::solve_zones(p), mp::SupercriticalSpeedError);
}

// Punches a million h apart are two independent single punches (solved as
// separate groups, each about its own axis: no table spans the distance),
// and a damped pair's dissipation is the sum of each one's.
TEST(Zones, PunchesAMillionApartAreEachTheSinglePunch) {
  const mp::AsymmetricSolution ref = damped_reference();
  mp::ZonesParams p = layer(0.5, 1.0, 0.3);
  p.punches = {cylinder(0.002, -5e5), cylinder(0.002, 5e5)};
  p.zones = {{0, -5e5 + ref.left(), -5e5 + ref.right()}, {1, 5e5 + ref.left(), 5e5 + ref.right()}};
  const mp::ZonesSolution z = mp::solve_zones(p);
  ASSERT_EQ(z.zones.size(), 2U);
  const double spacing = std::nextafter(5e5, 1e6) - 5e5;
  for (int k = 0; k < 2; ++k) {
    const double at = k == 0 ? -5e5 : 5e5;
    EXPECT_NEAR(z.zones[static_cast<std::size_t>(k)].left, at + ref.left(), 1e-9 + spacing);
    EXPECT_NEAR(z.zones[static_cast<std::size_t>(k)].right, at + ref.right(), 1e-9 + spacing);
    EXPECT_NEAR(z.drag[static_cast<std::size_t>(k)], ref.drag(), 1e-8 * std::fabs(ref.drag()));
    EXPECT_EQ(z.zones[static_cast<std::size_t>(k)].group, k);
  }
  EXPECT_NEAR(mp::zones_dissipation(z), z.drag_total, 1e-7 * z.drag_total);
}

// A punch too far from x = 0 for the doubles to hold its contact is refused,
// naming `at` (not "the starting zones must be disjoint").
TEST(Zones, APunchBeyondDoublePrecisionNamesAt) {
  mp::ZonesParams p = layer(0.2, 1.0, 0.0);
  p.punches = {cylinder(0.002, 1e20)};
  p.zones = {{0, 1e20 - 0.37, 1e20 + 0.37}};
  try {
    mp::solve_zones(p);
    FAIL() << "no exception";
  } catch (const mp::InvalidParameter& e) {
    EXPECT_EQ(e.name(), "at");
  }
}
