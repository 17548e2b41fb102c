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
// Several level sets (level_sets:): `solid_body: {level_set: [a, b]}` measures each named
// body with columns solid_a_..., solid_b_... and the gap between each pair (kernels/contact.hpp),
//   solid_gap_a_b, solid_contact_a_b   as above, the pair's gap: min of -(psi_a + psi_b) over cells
//                                  inside both bands (kernels/contact.hpp); negative: overlap
// and summary.json "solid_body" has "bodies" (per name, as above) and "pairs"; `pairs: false`
// leaves the pairs out (a bed of many bodies: N (N - 1) / 2 of them).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/field_names.hpp"
#include "core/index_space.hpp"
#include "effects/effect.hpp"
#include "effects/solid_body.hpp"
#include "kernels/contact.hpp"
#include "kernels/heaviside.hpp"
#include "levelset/params.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace {

// One gap that is tracked for contacts: a body against an obstacle, a face or another body.
struct Contact {
  explicit Contact(std::string n = "") : name(std::move(n)) {}
  std::string name;
  double gap = 0, minGap = 1e300, minGapT = 0, first = -1;
  int in = 0;
  std::vector<double> events;
  void update(double g, double time, double thr) {
    gap = g;
    if (gap < minGap) minGap = gap, minGapT = time;
    if (!in && gap < thr) {
      in = 1;
      if (first < 0) first = time;
      if (events.size() < 1000) events.push_back(time);
    } else if (in && gap > 1.5 * thr) {
      in = 0;
    }
  }
  nlohmann::json summary() const {
    return {{"first_contact_time", first < 0 ? nlohmann::json(nullptr) : nlohmann::json(first)},
            {"contact_start_times", events},
            {"min_gap", minGap},
            {"min_gap_time", minGapT},
            {"gap", gap}};
  }
};

// The checkpoint's form of a list of contacts (as before several bodies: one array per member).
nlohmann::json contactState(const std::vector<Contact>& cs) {
  nlohmann::json j = {{"first", nlohmann::json::array()}, {"events", nlohmann::json::array()},
                      {"in", nlohmann::json::array()},    {"min_gap", nlohmann::json::array()},
                      {"min_gap_time", nlohmann::json::array()}};
  for (const Contact& c : cs) {
    j["first"].push_back(c.first), j["events"].push_back(c.events), j["in"].push_back(c.in);
    j["min_gap"].push_back(c.minGap), j["min_gap_time"].push_back(c.minGapT);
  }
  return j;
}
void loadContacts(std::vector<Contact>& cs, const nlohmann::json& j) {
  for (size_t q = 0; q < cs.size(); ++q) {
    cs[q].first = j.at("first").at(q).get<double>();
    cs[q].events = j.at("events").at(q).get<std::vector<double>>();
    cs[q].in = j.at("in").at(q).get<int>();
    cs[q].minGap = j.at("min_gap").at(q).get<double>();
    cs[q].minGapT = j.at("min_gap_time").at(q).get<double>();
  }
}

struct Body {
  LevelSetInfo info;
  std::string prefix; // "solid_" for the single level_set, "solid_NAME_" for named bodies
  double rho = 0;
  std::vector<Contact> contacts; // one per target
};

class SolidBody : public Effect {
 public:
  std::string name() const override { return "solid_body"; }
  std::vector<std::string> dependsOn() const override { return {"level_set"}; }
  void configure(const Scene& s, const Published& pub) override {
    const Section sec = topSection(s, "solid_body");
    contacts_ = sec.boolean("contacts", true);
    contactCells_ = sec.number("contact_gap", 1.0, Range::positive());
    bending_ = sec.boolean("bending", true);
    pairsOn_ = sec.boolean("pairs", true); // several bodies: the gap between every two (N (N - 1) / 2 columns)
    std::vector<std::string> names;
    if (contacts_) {
      if (s.obstacles.size() + 6 > size_t(kSolidTargets)) sec.fail("contacts", "too many obstacles to track");
      for (size_t i = 0; i < s.obstacles.size(); ++i) {
        const Obstacle& o = s.obstacles[i];
        SolidTarget t;
        t.kind = o.kind == Obstacle::Kind::Sphere ? 0 : o.kind == Obstacle::Kind::Cylinder ? 1 : 2;
        t.axis = o.axis;
        t.r = o.radius;
        for (int d = 0; d < 3; ++d) t.c[d] = o.center[d], t.lo[d] = o.lo[d], t.hi[d] = o.hi[d];
        targets_.t[targets_.n++] = t;
        names.push_back("obstacle" + std::to_string(i));
      }
      for (int f = 0; f < 6; ++f) {
        if (s.periodic(f / 2)) continue;
        SolidTarget t;
        t.kind = 3 + f % 2;
        t.axis = f / 2;
        t.c[t.axis] = f % 2 ? s.hi[t.axis] : s.lo[t.axis];
        targets_.t[targets_.n++] = t;
        names.push_back(std::string(1, char('x' + f / 2)) + (f % 2 ? "+" : "-"));
      }
    }
    bodies_.clear();
    for (const LevelSetInfo& l : pub.select(sec, true)) {
      Body b;
      b.info = l;
      b.prefix = l.name.empty() ? "solid_" : "solid_" + l.name + "_";
      if (s.materials.count(l.phase)) b.rho = s.materials.at(l.phase).density;
      for (const std::string& n : names) b.contacts.emplace_back(n);
      bodies_.push_back(b);
    }
    pairs_.clear();
    for (size_t a = 0; pairsOn_ && a < bodies_.size(); ++a)
      for (size_t b = a + 1; b < bodies_.size(); ++b) pairs_.emplace_back(bodies_[a].info.name + "_" + bodies_[b].info.name);
    sec.finish();
    g_ = s.gravity;
  }
  void declareFields(FieldStore& f) const override {
    for (const Body& b : bodies_) f.declare(b.info.field, Centring::Cell, 1, name());
    f.declare(field::velocity, Centring::Node, 3, name());
  }
  void setup(State& st) override {
    const Grid& g = st.grid;
    hmin_ = LevelSetGeometry::hMin(g);
    double diag2 = 0;
    for (int d = 0; d < 3; ++d) diag2 += (g.hi[d] - g.lo[d]) * (g.hi[d] - g.lo[d]);
    diagonal_ = std::sqrt(diag2);
    binR_ = int(std::ceil(0.5 * diagonal_ / hmin_)) + 1; // columns cover the half diagonal
    const int nb = 2 * binR_ + 1;
    if (bending_) bins_ = Kokkos::View<double* [4], MemSpace>("solid_body_columns", size_t(nb) * nb);
    for (Body& b : bodies_)
      for (Contact& c : b.contacts) c = Contact{c.name};
    for (Contact& c : pairs_) c = Contact{c.name};
    measure(st, st.t); // fills every column before the first time-series row
  }
  void registerTasks(Pipeline& p) override {
    p.add(Stage::Diagnostics, name(), "solid centroid, velocity, orientation, bending, gaps, contacts",
          [this](State& st) { measure(st, st.t + st.dt); }); // t advances after the stages
  }
  void summary(const State& st, nlohmann::json& j) const override {
    auto contacts = [](const std::vector<Contact>& cs) {
      nlohmann::json c = nlohmann::json::object();
      for (const Contact& x : cs) c[x.name] = x.summary();
      return c;
    };
    j["solid_body"] = {{"contact_gap", contactCells_ * hmin_}, {"contact_gap_cells", contactCells_}};
    if (single()) {
      j["solid_body"]["contacts"] = contacts(bodies_[0].contacts);
      return;
    }
    for (const Body& b : bodies_) j["solid_body"]["bodies"][b.info.name] = {{"contacts", contacts(b.contacts)}};
    j["solid_body"]["pairs"] = contacts(pairs_);
  }
  void saveState(nlohmann::json& j) const override {
    if (single()) {
      j = contactState(bodies_[0].contacts);
      return;
    }
    for (const Body& b : bodies_) j["bodies"][b.info.name] = contactState(b.contacts);
    j["pairs"] = contactState(pairs_);
  }
  void loadState(const nlohmann::json& j) override {
    if (single()) return loadContacts(bodies_[0].contacts, j);
    for (Body& b : bodies_) loadContacts(b.contacts, j.at("bodies").at(b.info.name));
    loadContacts(pairs_, j.at("pairs"));
  }

 private:
  bool single() const { return bodies_.size() == 1 && bodies_[0].info.name.empty(); }
  void measure(State& st, double time);
  void measure(State& st, Body& b, double time);

  bool contacts_ = true, bending_ = true, pairsOn_ = true;
  double contactCells_ = 1, hmin_ = 1, diagonal_ = 1; // diagonal_: the domain's (setup)
  Vec3 g_{0, 0, 0};
  SolidTargets targets_;
  std::vector<Body> bodies_;
  std::vector<Contact> pairs_; // a-b for every two bodies, in the scene's order
  int binR_ = 0;
  Kokkos::View<double* [4], MemSpace> bins_;
};

void SolidBody::measure(State& st, double time) {
  for (Body& b : bodies_) measure(st, b, time);
  const Grid& g = st.grid;
  std::vector<double> gaps(pairs_.size(), 1e300); // this rank's, reduced in one message
  size_t q = 0;
  for (size_t a = 0; pairsOn_ && a < bodies_.size(); ++a)
    for (size_t c = a + 1; c < bodies_.size(); ++c, ++q) {
      // Several level sets: only where both boxes meet can both be within their bands.
      const Range3 both = within(st.activeBox(bodies_[a].info.field), 0,
                                 within(st.activeBox(bodies_[c].info.field), 0, cellRange(g)));
      if (both.e[0] <= both.b[0]) continue;
      // Within both bands psi is a distance; farther apart than that: the domain's diagonal.
      const double reach = std::min(bodies_[a].info.geometry.band(g), bodies_[c].info.geometry.band(g));
      gaps[q] = localBodyGap(st.fields.scalar(bodies_[a].info.field), st.fields.scalar(bodies_[c].info.field), reach, both);
    }
  if (!gaps.empty()) MPI_Allreduce(MPI_IN_PLACE, gaps.data(), int(gaps.size()), MPI_DOUBLE, MPI_MIN, g.comm);
  for (q = 0; q < pairs_.size(); ++q) {
    pairs_[q].update(std::min(gaps[q], diagonal_), time, contactCells_ * hmin_);
    st.diag["solid_gap_" + pairs_[q].name] = pairs_[q].gap;
    st.diag["solid_contact_" + pairs_[q].name] = pairs_[q].in;
  }
}

void SolidBody::measure(State& st, Body& body, double time) {
  const Grid& g = st.grid;
  const Field psi = st.fields.scalar(body.info.field);
  const VecField u = st.fields.vector(field::velocity);
  const double kappa = body.info.geometry.kappa(g), band = 2 * hmin_, hm = hmin_;
  const SolidTargets tg = targets_;
  // moments about the domain centre r; several level sets: on the body's box
  SolidAcc acc = solidMoments(g, psi, u, kappa, band, hm, tg, st.activeBox(body.info.field));
  const double r0 = 0.5 * (g.lo[0] + g.hi[0]), r1 = 0.5 * (g.lo[1] + g.hi[1]), r2 = 0.5 * (g.lo[2] + g.hi[2]);
  MPI_Allreduce(MPI_IN_PLACE, acc.s, kSolidSums, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, acc.m, kSolidTargets, MPI_DOUBLE, MPI_MIN, g.comm);
  auto& dg = st.diag;
  const std::string& P = body.prefix;
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
  dg[P + "volume"] = vol;
  dg[P + "cx"] = c[0], dg[P + "cy"] = c[1], dg[P + "cz"] = c[2];
  dg[P + "vx"] = vel[0], dg[P + "vy"] = vel[1], dg[P + "vz"] = vel[2];
  dg[P + "tilt_deg"] = tilt;
  dg[P + "angle_z_deg"] = angle;
  if (bending_)
    dg[P + "bending"] = bend;
  else
    dg.erase(P + "bending"); // a restart from a run that measured it: empty from here
  dg[P + "potential_energy"] = -body.rho * vol * (g_[0] * c[0] + g_[1] * c[1] + g_[2] * c[2]);
  const double thr = contactCells_ * hmin_;
  for (size_t q = 0; q < body.contacts.size(); ++q) {
    Contact& ct = body.contacts[q];
    ct.update(std::min(acc.m[q], diagonal_), time, thr); // no interface near: the domain's diagonal
    dg[P + "gap_" + ct.name] = ct.gap;
    dg[P + "contact_" + ct.name] = ct.in;
  }
}

} // namespace

std::unique_ptr<Effect> makeSolidBody() { return std::make_unique<SolidBody>(); }

} // namespace voigt
