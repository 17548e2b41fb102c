// pack_spheres: discrete-element gravity deposition of spheres in a duct, for the level-set
// shape sphere_packing (cases/porous_bed). Writes the CSV of centres and radii and a JSON
// report (N, bed height, voidage, coordination, bonding, Ergun pressure gradient).
// The same arguments and seed give a byte-identical CSV.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <iostream>

#include "packing.hpp"

using namespace pack;

namespace {

nlohmann::json contactJson(const ContactStats& s) {
  return {{"pairs", s.pairs},
          {"coordination", s.z},
          {"coordination_with_walls", s.zWalls},
          {"wall_contacts", s.wallContacts},
          {"spheres_without_sphere_contact", s.rattlers},
          {"overlap_over_d", {{"mean", s.overlapMean}, {"min", s.overlapMin}, {"max", s.overlapMax}}},
          {"components", s.components},
          {"largest_component", s.largest},
          {"spheres_not_anchored_to_hold_layer", s.unanchored},
          {"histogram", s.histogram}};
}

} // namespace

int main(int argc, char** argv) {
  PackConfig c;
  std::vector<double> duct{c.duct.x, c.duct.y, c.duct.z};
  std::vector<double> interior{0.10, 0.25};
  std::string csvPath = "packing.csv", reportPath;
  double gasU = 0.1, gasRho = 1, gasMu = 1e-5;
  bool quiet = false;

  CLI::App app{"Gravity deposition of spheres (soft-sphere DEM) in a duct; writes x,y,z,r CSV for sphere_packing"};
  app.add_option("--duct", duct, "duct size x,y,z in m (y vertical, gravity -y)")->expected(3)->delimiter(',')
      ->capture_default_str();
  app.add_option("-d,--diameter", c.diameter, "mean sphere diameter, m")->capture_default_str();
  app.add_option("--polydispersity", c.polydispersity, "diameters uniform in d(1 +- p)")->capture_default_str();
  app.add_option("--base", c.base, "y of the support plane the bed is poured onto, m")->capture_default_str();
  app.add_option("--bed-top", c.bedTop, "pour until the mean surface height reaches this y, m (if --count is 0)")
      ->capture_default_str();
  app.add_option("-n,--count", c.count, "number of spheres (0: fill to --bed-top)")->capture_default_str();
  app.add_option("--batch", c.batch, "spheres per pour (0: about one layer)")->capture_default_str();
  app.add_option("-s,--seed", c.seed, "random seed")->capture_default_str();
  app.add_option("--restitution", c.restitution, "normal coefficient of restitution")->capture_default_str();
  app.add_option("--friction", c.friction, "Coulomb friction coefficient, sphere-sphere")->capture_default_str();
  app.add_option("--wall-friction", c.wallFriction, "Coulomb friction coefficient, sphere-wall")
      ->capture_default_str();
  app.add_option("--density", c.density, "sphere density, kg/m^3")->capture_default_str();
  app.add_option("--stiffness-ratio", c.stiffnessRatio, "k_n d / (m g)")->capture_default_str();
  app.add_option("--dt-fraction", c.dtFraction, "time step / binary contact time")->capture_default_str();
  app.add_option("--ke-tol", c.keTol, "settled when kinetic energy per sphere < tol * m g d")->capture_default_str();
  app.add_option("--max-time", c.maxTime, "cap on simulated time, s")->capture_default_str();
  app.add_option("--inflate", c.inflate, "output radii = (1 + inflate) * settled radii (bonds contacts)")
      ->capture_default_str();
  app.add_option("--hold-width", c.holdWidth, "width of the scene's zero-velocity layer at the side walls, m")
      ->capture_default_str();
  app.add_option("--clearance", c.clearance, "remove spheres reaching within this distance of the duct top, m")
      ->capture_default_str();
  app.add_option("--interior", interior, "y range for the interior voidage and Ergun gradient, m")->expected(2)
      ->delimiter(',')->capture_default_str();
  app.add_option("--gas-velocity", gasU, "superficial gas velocity for Ergun, m/s")->capture_default_str();
  app.add_option("--gas-density", gasRho, "gas density for Ergun, kg/m^3")->capture_default_str();
  app.add_option("--gas-viscosity", gasMu, "gas viscosity for Ergun, Pa s")->capture_default_str();
  app.add_option("-o,--output", csvPath, "CSV of sphere centres and radii")->capture_default_str();
  app.add_option("--report", reportPath, "JSON report file (the report also goes to stdout)");
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  CLI11_PARSE(app, argc, argv);
  c.duct = {duct[0], duct[1], duct[2]};
  if (!quiet) c.log = [](const std::string& s) { std::cerr << s << "\n"; };

  try {
    const auto t0 = std::chrono::steady_clock::now();
    const PackResult r = deposit(c);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    {
      std::ofstream out(csvPath, std::ios::binary);
      if (!out) throw std::runtime_error("cannot write " + csvPath);
      out << toCsv(r.output);
    }
    const double d = c.diameter;
    const double h = surfaceHeight(r.dem, c);
    double ymax = c.base;
    for (const auto& s : r.dem) ymax = std::max(ymax, s.y + s.r);
    const Box bulk = ductSlab(c, c.base, h), core = ductSlab(c, c.base + d, h - d, d),
              inner = ductSlab(c, interior[0], interior[1]),
              flow = ductSlab(c, interior[0], interior[1], c.holdWidth);
    auto voids = [&](const std::vector<Sphere>& s) {
      nlohmann::json v{{"bulk", voidage(s, bulk)},
                       {"core", voidage(s, core)},
                       {"interior", voidage(s, inner)},
                       {"interior_flow_region", voidage(s, flow)}};
      nlohmann::json g;
      for (auto& [k, e] : v.items()) g[k] = ergun(e.get<double>(), gasU, gasRho, gasMu, d);
      return std::make_pair(v, g);
    };
    // If the hold layer (zero velocity) blocks the gas, the inflow passes the open core only.
    const double uCore = gasU * c.duct.x * c.duct.z / ((c.duct.x - 2 * c.holdWidth) * (c.duct.z - 2 * c.holdWidth));
    const auto [voidSettled, ergunSettled] = voids(r.dem);
    const auto [voidWritten, ergunWritten] = voids(r.output);
    // Solid-fraction profile over slabs of d/4, full cross-section.
    std::vector<double> profY, profPhi;
    for (double y = c.base; y < ymax; y += 0.25 * d) {
      profY.push_back(y + 0.125 * d);
      profPhi.push_back(1 - voidage(r.dem, ductSlab(c, y, y + 0.25 * d)));
    }
    nlohmann::json j;
    j["input"] = {{"duct", duct},
                  {"diameter", d},
                  {"polydispersity", c.polydispersity},
                  {"base", c.base},
                  {"bed_top_target", c.count > 0 ? nlohmann::json(nullptr) : nlohmann::json(c.bedTop)},
                  {"count", c.count},
                  {"seed", c.seed},
                  {"restitution", c.restitution},
                  {"friction", c.friction},
                  {"wall_friction", c.wallFriction},
                  {"density", c.density},
                  {"stiffness_ratio", c.stiffnessRatio},
                  {"dt_fraction", c.dtFraction},
                  {"ke_tol", c.keTol},
                  {"inflate", c.inflate},
                  {"hold_width", c.holdWidth},
                  {"clearance", c.clearance},
                  {"interior", interior}};
    j["N"] = r.dem.size();
    j["bed"] = {{"base", c.base},
                {"surface_height", h},
                {"highest_sphere_top", ymax},
                {"height", h - c.base},
                {"definitions",
                 "surface: mean over round(L/d)^2 columns of the highest sphere top; bulk: full cross-section, "
                 "base..surface; core: one diameter from side walls, base and surface; interior: full "
                 "cross-section over --interior; interior_flow_region: the same without the hold layer; exact "
                 "sphere-box volumes"}};
    j["voidage_settled"] = voidSettled;
    j["voidage_written"] = voidWritten;
    j["solid_fraction_profile"] = {{"y", profY}, {"phi", profPhi}};
    j["contacts_settled"] = contactJson(contacts(r.dem, c, 0.0));
    j["contacts_written"] = contactJson(contacts(r.output, c, 0.0));
    j["dem"] = {{"kn", r.kn},
                {"gravity_overlap_mg_over_k", r.mg / r.kn},
                {"contact_time", r.contactTime},
                {"dt", r.dt},
                {"steps", r.steps},
                {"pours", r.pours},
                {"trimmed_below_outlet", r.trimmed},
                {"settle_time", r.simTime},
                {"settled", r.settled},
                {"final_ke_over_mgd", r.finalKe},
                {"max_overlap_over_d", r.maxOverlap / d}};
    j["ergun"] = {{"velocity", gasU},
                  {"gas_density", gasRho},
                  {"gas_viscosity", gasMu},
                  {"reynolds", gasRho * gasU * d / gasMu},
                  {"formula", "Ergun (1952), paper Eq. (23), Pa/m, for each voidage above"},
                  {"gradient_settled", ergunSettled},
                  {"gradient_written", ergunWritten},
                  {"core_superficial_velocity", uCore},
                  {"gradient_written_flow_region_core_velocity",
                   ergun(voidWritten["interior_flow_region"].get<double>(), uCore, gasRho, gasMu, d)}};
    j["wall_time"] = wall;
    j["csv"] = csvPath;
    const std::string text = j.dump(2);
    std::cout << text << "\n";
    if (!reportPath.empty()) {
      std::ofstream rep(reportPath);
      if (!rep) throw std::runtime_error("cannot write " + reportPath);
      rep << text << "\n";
    }
    return r.settled ? 0 : 3;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
