// The medium interface (medium.hpp): the homogeneous layer behind it gives
// LayerModel's numbers exactly, keys the kernel cache as before, and the
// description is validated naming the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "movingpunch/contact.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/layer_response.hpp"
#include "movingpunch/medium.hpp"

using namespace movingpunch;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

TEST(Medium, HomogeneousLayerIsLayerModelBitForBit) {
  for (const double kw : {0.1, 1.0, kInf})
    for (const double kp : {0.0, 0.3})
      for (const double vstar : {0.0, 0.2, 0.5}) {
        const LayerModel ref(vstar, kw, 0.25, kp);
        const auto med = make_medium(homogeneous_medium(kw, 0.25, kp), vstar);
        ASSERT_TRUE(med->real());
        EXPECT_EQ(med->phi1(), ref.phi1());
        EXPECT_EQ(med->phi2(), ref.phi2());
        EXPECT_EQ(med->long_wave_m1(), 0.0);
        for (const double t : {1e-6, 0.3, 0.5, 2.0, 40.0}) {
          const Response r = ref.response(t);
          const MediumResponse m = med->surface_response(t);
          EXPECT_EQ(m.M1, cplx(r.M1, 0.0));
          EXPECT_EQ(m.M2, cplx(r.M2, 0.0));
          EXPECT_EQ(m.W0, cplx(r.W0, 0.0));
          EXPECT_EQ(med->dispersion(t), ref.dispersion(t));
          const ModeField f = ref.mode_field(t);
          const auto p = med->mode(t);
          for (const double y : {0.0, -0.3, -1.0}) {
            const Eigen::Vector4d z = f.state(y), h = f.half_plane_state(y);
            const ModeState s = p->state(y), r2 = p->remainder(y), hp = p->half_plane(y);
            for (int k = 0; k < 4; ++k) {
              EXPECT_EQ(s.z(k).real(), z(k));
              EXPECT_EQ(r2.z(k).real(), z(k) - h(k));
              EXPECT_EQ(hp.z(k).real(), h(k));
            }
            EXPECT_EQ(r2.sx.real(), sigma_x_hat(ref.constants(), z - h));
          }
        }
      }
}

TEST(Medium, TheKernelCacheKeysTheMediumAsItKeyedTheLayer) {
  clear_kernel_cache();
  bool built = false;
  cached_kernel(LayerModel(0.2, 1.0, 0.2, 0.1), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  // The same medium through the interface: the same table.
  cached_kernel(make_medium(homogeneous_medium(1.0, 0.2, 0.1), 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_FALSE(built);
  // kp is irrelevant on a rigid base: one key.
  cached_kernel(make_medium(homogeneous_medium(kInf, 0.2, 0.0), 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(make_medium(homogeneous_medium(kInf, 0.2, 7.0), 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_FALSE(built);
  // Another medium (a different nu): another table.
  cached_kernel(make_medium(homogeneous_medium(1.0, 0.3, 0.1), 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
}

TEST(Medium, ContactOnTheHomogeneousMediumIsTheShorthand) {
  ContactParams p;
  p.vstar = 0.3;
  p.kw = 2.0;
  p.nu = 0.3;
  p.tol = 1e-10;
  const SymmetricSolution a = solve_contact(p);
  ContactParams q = p;
  q.kw = 9.0;  // ignored: the medium's springs are the base's
  q.nu = 0.1;
  q.medium = std::make_shared<const MediumSpec>(homogeneous_medium(2.0, 0.3));
  const SymmetricSolution b = solve_contact(q);
  EXPECT_EQ(a.a(), b.a());
  EXPECT_EQ(a.indentation(), b.indentation());
  EXPECT_EQ(a.critical_vstar(), b.critical_vstar());
}

TEST(Medium, DescriptionsAreValidatedByName) {
  auto expect_named = [](const MediumSpec& m, const std::string& name) {
    try {
      validate(m);
      ADD_FAILURE() << "no error for " << name;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.name(), name) << e.what();
    }
  };
  MediumSpec m = homogeneous_medium(1.0, 0.2);
  EXPECT_NO_THROW(validate(m));
  m.layers = {Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.4, 2.0, 0.2, 1.0, 0.0}};
  expect_named(m, "layers");
  m.layers[1].thickness = 0.5;
  EXPECT_NO_THROW(validate(m));
  m.layers[0].mu = 2.0;
  expect_named(m, "layers[0].mu");
  m.layers[0].mu = 1.0;
  m.layers[1].nu = 0.5;
  expect_named(m, "layers[1].nu");
  m.layers[1].nu = 0.2;
  m.layers[1].gamma = 60.0;
  expect_named(m, "layers[1].gamma_h");
  m.layers[1].gamma = 0.0;
  m.base.kind = BaseKind::half_space_bonded;
  m.base.mu = -1.0;
  expect_named(m, "base.mu");
  m.base.mu = 1.0;
  m.base.rho = std::nan("");
  expect_named(m, "base.rho");
  m.layers.clear();
  expect_named(m, "layers");
  // A damped homogeneous layer is a medium of complex responses (the
  // asymmetric solver's: real() false); damped springs under a stack are not.
  EXPECT_FALSE(make_medium(homogeneous_medium(1.0, 0.2, 0.0, 0.5), 0.2)->real());
  MediumSpec damped_stack = homogeneous_medium(1.0, 0.2, 0.0, 0.5);
  damped_stack.layers = {Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}};
  EXPECT_THROW(make_medium(damped_stack, 0.2), std::invalid_argument);
}

TEST(Medium, DescribeNamesTheMedium) {
  EXPECT_EQ(describe(homogeneous_medium(1.0, 0.2, 0.2)), "kw = 1, kp = 0.2");
  MediumSpec m;
  m.layers = {Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.5, 2.0, 0.3, 1.0, 1.5}};
  m.base.kind = BaseKind::half_space_smooth;
  m.base.mu = 10.0;
  m.base.nu = 0.3;
  m.base.rho = 2.0;
  EXPECT_EQ(describe(m), "2 sublayers (1 graded) on a smooth half-space (mu 10, nu 0.3, rho 2)");
}

// A field table drives validate() and the cache key: every field of `table`
// out of its range (just past each end, and NaN) is refused naming
// prefix + "<field>"; a change of any field changes the key. `part(m)` is the
// struct the table's members belong to (a sublayer, the base) in medium m.
template <class Table, class Part>
void expect_table_validated_and_keyed(const MediumSpec& ok, const Table& table, Part part,
                                      const std::string& prefix) {
  ASSERT_NO_THROW(validate(ok));
  for (const auto& f : table) {
    const double span = std::isfinite(f.hi - f.lo) ? f.hi - f.lo : 1.0;
    for (const double bad :
         {f.lo - 1e-3 * span, f.hi + 1e-3 * span, std::numeric_limits<double>::quiet_NaN()}) {
      MediumSpec m = ok;
      part(m).*f.member = bad;
      try {
        validate(m);
        ADD_FAILURE() << f.name << " = " << bad << " accepted";
      } catch (const InvalidParameter& e) {
        EXPECT_EQ(e.name(), prefix + f.name) << e.what();
      }
    }
    MediumSpec moved = ok;
    part(moved).*f.member = 0.5 * (part(moved).*f.member + 0.45);
    EXPECT_NE(moved.key(), ok.key()) << f.name;
  }
}

TEST(Medium, EverySublayerFieldIsValidatedAndKeyedByTheTable) {
  MediumSpec ok;
  ok.layers = {Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.5, 0.5, 0.3, 0.8, 0.5}};
  expect_table_validated_and_keyed(
      ok, kSublayerFields, [](MediumSpec& m) -> Sublayer& { return m.layers[1]; }, "layers[1].");
}

// The half-space's table also drives describe(), on both interfaces.
TEST(Medium, EveryHalfSpaceFieldIsValidatedKeyedAndDescribedByTheTable) {
  for (const BaseKind kind : {BaseKind::half_space_bonded, BaseKind::half_space_smooth}) {
    MediumSpec ok;
    ok.layers = {Sublayer{1.0, 1.0, 0.2, 1.0, 0.0}};
    ok.base.kind = kind;
    ok.base.mu = 0.5;
    ok.base.nu = 0.3;
    ok.base.rho = 0.8;
    expect_table_validated_and_keyed(
        ok, kHalfSpaceFields, [](MediumSpec& m) -> BaseSpec& { return m.base; }, "base.");
    for (const HalfSpaceField& f : kHalfSpaceFields) {
      std::ostringstream shown;
      shown << f.name << " " << ok.base.*f.member;
      EXPECT_NE(describe(ok).find(shown.str()), std::string::npos) << describe(ok);
    }
  }
}
