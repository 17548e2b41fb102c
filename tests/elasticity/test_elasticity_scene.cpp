// The elasticity effect's scene plumbing (unit): no stress fields without
// `elasticity`; shear modulus from E and nu; the elastic-wave dt limit; the
// diagnostics exist from set-up; `rotation` default and choice; bad keys and
// inconsistent moduli refused with the key named.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <string>

#include "effects/elasticity/elasticity.hpp"
#include "kernels/elastic.hpp"
#include "scene/reader.hpp"
#include "support/flow.hpp"

using namespace voigt;

using test::sceneErrorOf;

TEST(ElasticityScene, NoStressFieldsWithoutElasticity) {
  auto s = test::scene(
      "domain: {cells: [8,8,8]}\n"
      "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\nfluid: air\n"
      "effects: [navier_stokes, level_set]\n"
      "level_set: {phase: rubber, shape: {type: sphere, center: [0.5,0.5,0.5], radius: 0.2}}\n"
      "output: {enabled: false}\n");
  Simulation sim(s, MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  for (auto& n : sim.state().fields.allocatedNames()) {
    EXPECT_EQ(n.rfind("solid_stress", 0), std::string::npos) << n;
    EXPECT_NE(n, "S2");
    EXPECT_NE(n, "log10_S2");
  }
  EXPECT_EQ(sim.effect("elasticity"), nullptr);
}

TEST(ElasticityScene, ModuliAndErrors) {
  const std::string base =
      "domain: {cells: [8,8,8]}\nfluid: air\neffects: [navier_stokes, level_set, elasticity]\n"
      "level_set: {phase: rubber, shape: {type: sphere, center: [0.5,0.5,0.5], radius: 0.2}}\n"
      "output: {enabled: false}\n";
  // E and nu: mu_S = E / (2 (1 + nu)).
  {
    Simulation sim(test::scene(base + "materials: {rubber: {density: 100, youngs_modulus: 3000, poisson_ratio: 0.5},"
                                      " air: {density: 1}}\n"),
                   MPI_COMM_WORLD, RunOptions{});
    sim.initialize();
    auto* e = dynamic_cast<Elasticity*>(sim.effect("elasticity"));
    ASSERT_NE(e, nullptr);
    EXPECT_DOUBLE_EQ(e->shearModulus(), 1000.0);
    EXPECT_DOUBLE_EQ(e->kelvinVoigtViscosity(), 0.0);
    EXPECT_EQ(e->rotation(), elastic::Rotation::Cayley); // the default
    nlohmann::json j;
    e->summary(sim.state(), j);
    EXPECT_EQ(j["elasticity"]["rotation"], "cayley");
    const DtLimit l = sim.stableDt();
    EXPECT_EQ(l.reason, "elastic wave");
    EXPECT_NEAR(l.dt, 0.5 * (1.0 / 8) / std::sqrt(1000.0 / 100), 1e-15);
    for (const char* k : {"elastic_energy", "max_S2", "stress_cells"}) EXPECT_TRUE(sim.state().diag.count(k)) << k;
  }
  std::string e = sceneErrorOf(base + "materials: {rubber: {density: 100, shear_modulus: 1000, youngs_modulus: 3000,"
                                 " poisson_ratio: 0.5}, air: {density: 1}}\n");
  EXPECT_NE(e.find("youngs_modulus"), std::string::npos) << e;
  e = sceneErrorOf(base + "materials: {rubber: {density: 100, youngs_modulus: 3000}, air: {density: 1}}\n");
  EXPECT_NE(e.find("poisson_ratio"), std::string::npos) << e;
  e = sceneErrorOf(base + "materials: {rubber: {density: 100}, air: {density: 1}}\n");
  EXPECT_NE(e.find("shear_modulus"), std::string::npos) << e;
  e = sceneErrorOf(base + "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
                     "elasticity: {bnad: 3}\n");
  EXPECT_NE(e.find("bnad"), std::string::npos) << e;
  e = sceneErrorOf(base + "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
                     "elasticity: {initial_stress: {xz: 1}}\n");
  EXPECT_NE(e.find("xz"), std::string::npos) << e;
  {
    Simulation sim(test::scene(base + "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
                                      "elasticity: {rotation: explicit}\n"),
                   MPI_COMM_WORLD, RunOptions{});
    sim.initialize();
    auto* el = dynamic_cast<Elasticity*>(sim.effect("elasticity"));
    ASSERT_NE(el, nullptr);
    EXPECT_EQ(el->rotation(), elastic::Rotation::Explicit);
    nlohmann::json j;
    el->summary(sim.state(), j);
    EXPECT_EQ(j["elasticity"]["rotation"], "explicit");
  }
  e = sceneErrorOf(base + "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
                     "elasticity: {rotation: jaumann}\n");
  EXPECT_NE(e.find("rotation"), std::string::npos) << e;
  e = sceneErrorOf(base + "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
                     "elasticity: {fluid_side: solid}\n");
  EXPECT_NE(e.find("fluid_side"), std::string::npos) << e;
  for (const char* side : {"integrate", "extend", "blend"}) {
    Simulation sim(test::scene(base + "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
                                      "elasticity: {fluid_side: " + side + "}\n"),
                   MPI_COMM_WORLD, RunOptions{});
    sim.initialize();
    nlohmann::json j;
    sim.effect("elasticity")->summary(sim.state(), j);
    EXPECT_EQ(j["elasticity"]["fluid_side"], side);
  }
  e = sceneErrorOf("domain: {cells: [8,8,8]}\neffects: [navier_stokes, elasticity]\noutput: {enabled: false}\n");
  EXPECT_NE(e.find("level_set"), std::string::npos) << e;
}

// The neo-Hookean solid's dt limit and energy from its current state (issue 53): a body
// stretched isochorically along x by 2 (B = diag(4, 1/2, 1/2), tau_S = mu_S (B - I) = (3, -1/2,
// -1/2) mu_S) has rho c^2 = mu_S + 3 mu_S along x, so the elastic limit halves; its energy is
// INT H mu_S (tr B - 3) / 2 = mu_S per unit volume, where the hypoelastic solid's, INT H tau:tau /
// (4 mu_S), is 9.5 mu_S / 4. The sphere covers the unit box (H = 1 everywhere): 1000 J and
// 2375 J. det B = 1, so the drift column reads 0. `voigt check` names the model.
TEST(ElasticityScene, NeoHookeanDtAndEnergyFromTheCurrentStretch) {
  const std::string base =
      "domain: {cells: [8,8,8]}\nfluid: air\neffects: [navier_stokes, level_set, elasticity]\n"
      "level_set: {phase: rubber, shape: {type: sphere, center: [0.5,0.5,0.5], radius: 2}}\n"
      "materials: {rubber: {density: 100, shear_modulus: 1000}, air: {density: 1}}\n"
      "output: {enabled: false}\n";
  double energy[2];
  for (int nh = 0; nh < 2; ++nh) {
    Simulation sim(test::scene(base + "elasticity: {initial_stress: {xx: 3000, yy: -500, zz: -500}" +
                               (nh ? ", model: neo_hookean}\n" : "}\n")),
                   MPI_COMM_WORLD, RunOptions{});
    sim.initialize();
    const double c0 = std::sqrt(1000.0 / 100), dt0 = 0.5 * (1.0 / 8) / c0;
    EXPECT_NEAR(sim.stableDt().dt, nh ? dt0 / 2 : dt0, 1e-15) << (nh ? "neo_hookean" : "hypoelastic");
    energy[nh] = sim.state().diag.at("elastic_energy");
    if (nh) EXPECT_NEAR(sim.state().diag.at("det_B_drift"), 0.0, 1e-14);
    const std::string d = sim.describe();
    EXPECT_NE(d.find(nh ? "neo-Hookean solid" : "hypoelastic solid"), std::string::npos) << d;
  }
  EXPECT_NEAR(energy[0], 2375.0, 1e-9); // tau:tau / (4 mu_S) over the unit box
  EXPECT_NEAR(energy[1], 1000.0, 1e-9); // mu_S (tr B - 3) / 2
}
