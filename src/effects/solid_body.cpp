// solid_body: diagnostics of the level set's solid (psi > 0, the falling block
// of cases/falling_block) every step, in timeseries.csv and summary.json.
// Scene: `effects: [..., level_set, solid_body]`, optional section
//   solid_body: {contacts: true, contact_gap: 1, bending: true}   # gap threshold in cells
// bending: false leaves out solid_bending (a plate's measure: a bed of spheres has no
// mid-surface), its column sums being the effect's costliest pass over the cells.
// Measures (all weighted by the smoothed Heaviside w = H(psi) of Eq. 4, so the
// solid's smoothing band counts as in the blended density, and MPI-reduced):
//   solid_volume, solid_cx/cy/cz   sum w dV and the w-weighted centroid
//   solid_vx/vy/vz                 w-weighted mean of the cell velocity (mean of 8 corners)
//   solid_tilt_deg                 angle of the thin axis n (eigenvector of the smallest
//                                  eigenvalue of the w-weighted second-moment tensor about
//                                  the centroid; n_y >= 0) from +y: acos(n_y)
//   solid_angle_z_deg              atan2(-n_x, n_y): the thin axis' turn about z, in (-90, 90]
//   solid_bending                  in the principal frame (a, b along the two larger axes,
//                                  s along n), columns centred h apart in (a, b), each cell
//                                  shared bilinearly among its 4 nearest columns (w times the
//                                  tent weights, so no cell jumps between columns); each column
//                                  with at least one cell of solid (sum >= 1) gives a
//                                  mid-surface point, the weighted mean (a, b, s); bending is
//                                  the largest |s - plane(a, b)| over columns, the plane being
//                                  their least-squares fit s = p0 + p1 a + p2 b (equal weights).
//                                  The smoothed profile is symmetric across the thickness, so
//                                  a flat solid gives the mid-plane to sampling error; the tent
//                                  attenuates a bend of wavelength L by sinc^2(pi h / L).
//   solid_potential_energy         -rho_solid V g . centroid (J, zero at the origin)
//   solid_gap_<target>             smallest distance between the surface psi = 0 and an
//                                  obstacle (obstacle<i>) or domain face (x-, ..., z+):
//                                  min over cells with -2 h < psi < h of d_target(x) - psi(x)
//                                  (fluid cells inside any obstacle are skipped: the fixed
//                                  velocity there leaves psi stale, not a distance).
//                                  Where psi is a signed distance this bounds the gap from
//                                  above and equals it on the segment joining the closest
//                                  points, which lies outside the solid, so it is sub-cell
//                                  accurate (sharp cells: h/2). Cells deeper inside are left
//                                  out: psi overshoots near the mid-surface ridge (Fast
//                                  Marching, transport, re-initialisation all smooth the kink).
//   solid_contact_<target>         1 while in contact: a contact starts when the gap falls
//                                  below contact_gap * h and ends when it exceeds 1.5 times
//                                  that (hysteresis, so one touch is one event).
// summary.json "solid_body": first contact time and every contact start per target.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/field_names.hpp"
#include "core/index_space.hpp"
#include "effects/effect.hpp"
#include "effects/solid_body.hpp"
#include "kernels/heaviside.hpp"
#include "levelset/params.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace {

class SolidBody : public Effect {
 public:
  std::string name() const override { return "solid_body"; }
  std::vector<std::string> dependsOn() const override { return {"level_set"}; }
  void configure(const Scene& s, const Published& pub) override {
    const Section sec = topSection(s, "solid_body");
    contacts_ = sec.boolean("contacts", true);
    contactCells_ = sec.number("contact_gap", 1.0, Range::positive());
    bending_ = sec.boolean("bending", true);
    if (contacts_) {
      if (s.obstacles.size() + 6 > size_t(kSolidTargets)) sec.fail("contacts", "too many obstacles to track");
      for (size_t i = 0; i < s.obstacles.size(); ++i) {
        const Obstacle& o = s.obstacles[i];
        SolidTarget t;
        t.kind = o.kind == Obstacle::Kind::Sphere ? 0 : o.kind == Obstacle::Kind::Cylinder ? 1 : 2;
        t.axis = o.axis;
        t.r = o.radius;
        for (int d = 0; d < 3; ++d) t.c[d] = o.center[d], t.lo[d] = o.lo[d], t.hi[d] = o.hi[d];
        add(t, "obstacle" + std::to_string(i));
      }
      for (int f = 0; f < 6; ++f) {
        if (s.periodic(f / 2)) continue;
        SolidTarget t;
        t.kind = 3 + f % 2;
        t.axis = f / 2;
        t.c[t.axis] = f % 2 ? s.hi[t.axis] : s.lo[t.axis];
        add(t, std::string(1, char('x' + f / 2)) + (f % 2 ? "+" : "-"));
      }
    }
    sec.finish();
    geo_ = pub.levelSet;
    if (s.materials.count(pub.phase)) rhoSolid_ = s.materials.at(pub.phase).density;
    g_ = s.gravity;
  }
  void declareFields(FieldStore& f) const override {
    f.declare(field::psi, Centring::Cell, 1, name());
    f.declare(field::velocity, Centring::Node, 3, name());
  }
  void setup(State& st) override {
    const Grid& g = st.grid;
    hmin_ = LevelSetGeometry::hMin(g);
    double diag2 = 0;
    for (int d = 0; d < 3; ++d) diag2 += (g.hi[d] - g.lo[d]) * (g.hi[d] - g.lo[d]);
    binR_ = int(std::ceil(0.5 * std::sqrt(diag2) / hmin_)) + 1; // columns cover the half diagonal
    const int nb = 2 * binR_ + 1;
    if (bending_) bins_ = Kokkos::View<double* [4], MemSpace>("solid_body_columns", size_t(nb) * nb);
    const size_t n = names_.size();
    gap_.assign(n, 0.0), minGap_.assign(n, 1e300), minGapT_.assign(n, 0.0), first_.assign(n, -1.0);
    in_.assign(n, 0), events_.assign(n, {});
    measure(st, st.t); // fills every column before the first time-series row
  }
  void registerTasks(Pipeline& p) override {
    p.add(Stage::Diagnostics, name(), "solid centroid, velocity, orientation, bending, gaps, contacts",
          [this](State& st) { measure(st, st.t + st.dt); }); // t advances after the stages
  }
  void summary(const State& st, nlohmann::json& j) const override {
    nlohmann::json c = nlohmann::json::object();
    for (size_t q = 0; q < names_.size(); ++q)
      c[names_[q]] = {{"first_contact_time", first_[q] < 0 ? nlohmann::json(nullptr) : nlohmann::json(first_[q])},
                      {"contact_start_times", events_[q]},
                      {"min_gap", minGap_[q]},
                      {"min_gap_time", minGapT_[q]},
                      {"gap", gap_[q]}};
    j["solid_body"] = {{"contact_gap", contactCells_ * hmin_}, {"contact_gap_cells", contactCells_},
                       {"contacts", c}};
  }
  void saveState(nlohmann::json& j) const override {
    j = {{"first", first_}, {"events", events_}, {"in", in_}, {"min_gap", minGap_}, {"min_gap_time", minGapT_}};
  }
  void loadState(const nlohmann::json& j) override {
    first_ = j.at("first").get<std::vector<double>>();
    events_ = j.at("events").get<std::vector<std::vector<double>>>();
    in_ = j.at("in").get<std::vector<int>>();
    minGap_ = j.at("min_gap").get<std::vector<double>>();
    minGapT_ = j.at("min_gap_time").get<std::vector<double>>();
  }

 private:
  void add(const SolidTarget& t, const std::string& n) {
    targets_.t[targets_.n++] = t;
    names_.push_back(n);
  }
  void measure(State& st, double time);

  bool contacts_ = true, bending_ = true;
  double contactCells_ = 1, rhoSolid_ = 0, hmin_ = 1;
  Vec3 g_{0, 0, 0};
  LevelSetGeometry geo_;
  SolidTargets targets_;
  std::vector<std::string> names_;
  int binR_ = 0;
  Kokkos::View<double* [4], MemSpace> bins_;
  std::vector<double> gap_, minGap_, minGapT_, first_;
  std::vector<int> in_;
  std::vector<std::vector<double>> events_;
};

void SolidBody::measure(State& st, double time) {
  const Grid& g = st.grid;
  const Field psi = st.fields.scalar(field::psi);
  const VecField u = st.fields.vector(field::velocity);
  const double kappa = geo_.kappa(g), band = 2 * hmin_, hm = hmin_;
  const SolidTargets tg = targets_;
  SolidAcc acc = solidMoments(g, psi, u, kappa, band, hm, tg); // moments about the domain centre r
  const double r0 = 0.5 * (g.lo[0] + g.hi[0]), r1 = 0.5 * (g.lo[1] + g.hi[1]), r2 = 0.5 * (g.lo[2] + g.hi[2]);
  MPI_Allreduce(MPI_IN_PLACE, acc.s, kSolidSums, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, acc.m, kSolidTargets, MPI_DOUBLE, MPI_MIN, g.comm);
  auto& dg = st.diag;
  const double W = acc.s[0];
  double c[3] = {r0, r1, r2}, e[3][3] = {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}}; // e[0] thin axis, e[1], e[2]
  double vel[3] = {0, 0, 0}, tilt = 0, angle = 0, bend = 0;
  if (W > 0) {
    double m[3], cov[3][3];
    for (int d = 0; d < 3; ++d) m[d] = acc.s[1 + d] / W, c[d] += m[d], vel[d] = acc.s[4 + d] / W;
    const int off[3][3] = {{7, 10, 12}, {10, 8, 11}, {12, 11, 9}};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov[a][b] = acc.s[off[a][b]] / W - m[a] * m[b];
    double ev[3], vec[3][3];
    eigenSym3(cov, ev, vec);
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int p, int q) { return ev[p] < ev[q]; });
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d) e[a][d] = vec[d][order[a == 0 ? 0 : a == 1 ? 2 : 1]];
    if (e[0][1] < 0)
      for (int d = 0; d < 3; ++d) e[0][d] = -e[0][d];
    tilt = std::acos(std::min(1.0, std::fabs(e[0][1]))) * 180 / M_PI;
    angle = std::atan2(-e[0][0], e[0][1]) * 180 / M_PI;
    if (bending_) bend = solidBending(g, psi, kappa, hmin_, binR_, bins_, c, e);
  }
  const double vol = W * g.cellVolume();
  dg["solid_volume"] = vol;
  dg["solid_cx"] = c[0], dg["solid_cy"] = c[1], dg["solid_cz"] = c[2];
  dg["solid_vx"] = vel[0], dg["solid_vy"] = vel[1], dg["solid_vz"] = vel[2];
  dg["solid_tilt_deg"] = tilt;
  dg["solid_angle_z_deg"] = angle;
  if (bending_)
    dg["solid_bending"] = bend;
  else
    dg.erase("solid_bending"); // a restart from a run that measured it: empty from here
  dg["solid_potential_energy"] = -rhoSolid_ * vol * (g_[0] * c[0] + g_[1] * c[1] + g_[2] * c[2]);
  double diag2 = 0;
  for (int d = 0; d < 3; ++d) diag2 += (g.hi[d] - g.lo[d]) * (g.hi[d] - g.lo[d]);
  const double thr = contactCells_ * hmin_;
  for (size_t q = 0; q < names_.size(); ++q) {
    gap_[q] = std::min(acc.m[q], std::sqrt(diag2)); // no interface near: the domain's diagonal
    if (gap_[q] < minGap_[q]) minGap_[q] = gap_[q], minGapT_[q] = time;
    if (!in_[q] && gap_[q] < thr) {
      in_[q] = 1;
      if (first_[q] < 0) first_[q] = time;
      if (events_[q].size() < 1000) events_[q].push_back(time);
    } else if (in_[q] && gap_[q] > 1.5 * thr) {
      in_[q] = 0;
    }
    dg["solid_gap_" + names_[q]] = gap_[q];
    dg["solid_contact_" + names_[q]] = in_[q];
  }
}

} // namespace

std::unique_ptr<Effect> makeSolidBody() { return std::make_unique<SolidBody>(); }

} // namespace voigt
