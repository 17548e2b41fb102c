// Soft-sphere discrete-element method (DEM) for gravity deposition of spheres in a box.
//
// Contact model (Cundall & Strack 1979, "A discrete numerical model for granular
// assemblies", Geotechnique 29, 47-65):
//   normal:     linear spring-dashpot  F_n = (k_n delta + c_n d(delta)/dt) n,
//               c_n = 2 zeta sqrt(m_eff k_n), zeta = -ln e / sqrt(pi^2 + ln^2 e), so that a
//               binary collision has coefficient of restitution exactly e (the force is not
//               clipped at zero: that is what makes e exact; the short tensile tail at the end of
//               a damped contact is the usual price of the linear model);
//   tangential: linear spring k_t = (2/7) k_n on the accumulated tangential displacement
//               (kept per contact, projected onto the current tangent plane) plus a dashpot,
//               capped by Coulomb friction |F_t| <= mu |F_n| (sliding resets the spring);
//   walls:      planes (the duct's four sides and the floor/support), same law with m_eff = m.
// Gravity is -g along y. Integration: velocity Verlet (half-kick, drift, forces, half-kick),
// translational and rotational. dt is a fraction of the binary contact time
// t_c = pi sqrt(m_eff / k_n) of the two lightest spheres. Neighbour search: a cell list
// (cell >= largest diameter) rebuilt every step, so a step costs O(N).
//
// Everything is sequential and iterates in index order: the same input gives bit-identical
// output on the same build.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace pack {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  Vec3() = default;
  Vec3(double a, double b, double c) : x(a), y(b), z(c) {}
  double operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
  double& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
inline Vec3& operator-=(Vec3& a, Vec3 b) { return a = a - b; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

constexpr double kPi = 3.14159265358979323846;

// Damping ratio that gives restitution e for the linear spring-dashpot.
inline double dampingRatio(double e) {
  if (!(e > 0 && e <= 1)) throw std::invalid_argument("restitution must be in (0, 1]");
  const double l = std::log(e);
  return -l / std::sqrt(kPi * kPi + l * l);
}

struct DemParams {
  double gravity = 9.81;      // m/s^2, along -y
  double density = 10;        // kg/m^3 (only ratios matter for the geometry)
  double kn = 0;              // normal stiffness, N/m (set by the caller)
  double ktRatio = 2.0 / 7.0; // k_t / k_n
  double restitution = 0.6;   // normal coefficient of restitution
  double friction = 0.5;      // Coulomb coefficient, sphere-sphere
  double wallFriction = 0.5;  // Coulomb coefficient, sphere-wall
  double dt = 0;              // set by Dem::setTimeStep
  // Box: side walls at x = lo.x, hi.x and z = lo.z, hi.z; floor at y = lo.y; open top.
  Vec3 lo{0, 0, 0}, hi{0.11, 0.33, 0.11};
  bool sideWalls = true;
};

struct Particle {
  Vec3 x, v, w;       // position, velocity, angular velocity
  Vec3 f, t;          // force, torque
  double r = 0, m = 0, inertia = 0;
};

class Dem {
 public:
  explicit Dem(const DemParams& p) : p_(p) { zeta_ = dampingRatio(p.restitution); }

  const DemParams& params() const { return p_; }
  std::vector<Particle>& particles() { return ps_; }
  const std::vector<Particle>& particles() const { return ps_; }
  double time() const { return time_; }
  long steps() const { return steps_; }

  void add(Vec3 x, double r, Vec3 v = {}) {
    Particle q;
    q.x = x;
    q.v = v;
    q.r = r;
    q.m = p_.density * 4.0 / 3.0 * kPi * r * r * r;
    q.inertia = 0.4 * q.m * r * r;
    ps_.push_back(q);
    forcesValid_ = false;
  }

  // Removes the particles for which drop[i] is true; contact histories follow the survivors.
  void remove(const std::vector<bool>& drop) {
    std::vector<int> to(ps_.size(), -1);
    std::size_t n = 0;
    for (std::size_t i = 0; i < ps_.size(); ++i)
      if (!drop[i]) to[i] = int(n++);
    for (std::size_t i = 0; i < ps_.size(); ++i) {
      if (drop[i]) continue;
      std::vector<Contact> h;
      for (const auto& c : hist_[i])
        if (c.j < 0 || !drop[c.j]) h.push_back({c.j < 0 ? c.j : to[c.j], c.xi});
      ps_[to[i]] = ps_[i];
      hist_[to[i]] = std::move(h);
    }
    ps_.resize(n);
    hist_.resize(n);
    forcesValid_ = false;
  }

  // Binary contact time of the two lightest spheres (undamped).
  double contactTime() const {
    double mmin = std::numeric_limits<double>::max();
    for (const auto& q : ps_) mmin = std::min(mmin, q.m);
    return kPi * std::sqrt(0.5 * mmin / p_.kn);
  }
  void setTimeStep(double fractionOfContactTime) { p_.dt = fractionOfContactTime * contactTime(); }
  void setTimeStepAbsolute(double dt) { p_.dt = dt; }

  // One velocity-Verlet step.
  void step() {
    const double dt = p_.dt;
    if (!(dt > 0)) throw std::logic_error("Dem: time step not set");
    if (!forcesValid_) computeForces();
    for (auto& q : ps_) {
      q.v += (0.5 * dt / q.m) * q.f;
      q.w += (0.5 * dt / q.inertia) * q.t;
      q.x += dt * q.v;
    }
    computeForces();
    for (auto& q : ps_) {
      q.v += (0.5 * dt / q.m) * q.f;
      q.w += (0.5 * dt / q.inertia) * q.t;
    }
    time_ += dt;
    ++steps_;
  }

  // Kinetic energy (translational + rotational) per particle, J.
  double kineticEnergyPerParticle() const {
    if (ps_.empty()) return 0;
    double e = 0;
    for (const auto& q : ps_) e += 0.5 * q.m * dot(q.v, q.v) + 0.5 * q.inertia * dot(q.w, q.w);
    return e / double(ps_.size());
  }
  double maxSpeed() const {
    double s = 0;
    for (const auto& q : ps_) s = std::max(s, norm(q.v));
    return s;
  }
  double maxOverlap() const { return maxOverlap_; }
  int contactCount() const { return nContacts_; }

 private:
  struct Contact {
    int j;   // other particle (>= 0) or wall (-1 - wall id)
    Vec3 xi; // accumulated tangential spring displacement
  };

  // Force of one contact on particle i (and its reaction on j if j >= 0).
  // n: unit normal from the contact partner towards i; delta: overlap;
  // ri, rj: lever arms from the centres to the contact point; meff: effective mass.
  void contact(Particle& a, Particle* b, Vec3 n, double delta, double ri, double rj, double meff, double mu,
               Vec3& xi) {
    const double kn = p_.kn, kt = p_.ktRatio * p_.kn;
    const double cn = 2 * zeta_ * std::sqrt(meff * kn), ct = 2 * zeta_ * std::sqrt(meff * kt);
    Vec3 vrel = a.v - ri * cross(a.w, n);
    if (b) vrel -= b->v + rj * cross(b->w, n);
    const double vn = dot(vrel, n);
    const Vec3 vt = vrel - vn * n;
    const double fnMag = kn * delta - cn * vn;
    const Vec3 fn = fnMag * n;
    // Tangential spring: keep it in the current tangent plane (same length), then accumulate.
    const double xiLen = norm(xi);
    xi -= dot(xi, n) * n;
    const double xiLen2 = norm(xi);
    if (xiLen2 > 0) xi = (xiLen / xiLen2) * xi;
    xi += p_.dt * vt;
    Vec3 ft = -kt * xi - ct * vt;
    const double ftMag = norm(ft), fmax = mu * std::max(fnMag, 0.0);
    if (ftMag > fmax) {
      ft = (ftMag > 0 ? fmax / ftMag : 0.0) * ft;
      xi = (-1.0 / kt) * (ft + ct * vt); // sliding: spring holds what friction allows
    }
    a.f += fn + ft;
    a.t -= ri * cross(n, ft);
    if (b) {
      b->f -= fn + ft;
      b->t -= rj * cross(n, ft);
    }
    maxOverlap_ = std::max(maxOverlap_, delta);
    ++nContacts_;
  }

  Vec3* findHistory(int i, int j) {
    for (auto& c : histOld_[i])
      if (c.j == j) return &c.xi;
    return nullptr;
  }

  void computeForces() {
    const std::size_t n = ps_.size();
    maxOverlap_ = 0;
    nContacts_ = 0;
    histOld_.swap(hist_); // last step's contacts; hist_ is refilled (capacity kept)
    histOld_.resize(n);
    hist_.resize(n);
    for (auto& h : hist_) h.clear();
    for (auto& q : ps_) {
      q.f = Vec3(0, -p_.gravity * q.m, 0);
      q.t = Vec3();
    }
    if (n == 0) return;
    buildCells();
    const double mu = p_.friction, muw = p_.wallFriction;
    for (std::size_t i = 0; i < n; ++i) {
      Particle& a = ps_[i];
      // Walls: floor (id 0), x- (1), x+ (2), z- (3), z+ (4). Normal points into the box.
      auto wall = [&](int id, double dist, Vec3 nrm) {
        const double delta = a.r - dist;
        if (delta <= 0) return;
        Vec3 xi;
        if (Vec3* h = findHistory(int(i), -1 - id)) xi = *h;
        contact(a, nullptr, nrm, delta, a.r, 0, a.m, muw, xi);
        hist_[i].push_back({-1 - id, xi});
      };
      wall(0, a.x.y - p_.lo.y, {0, 1, 0});
      if (p_.sideWalls) {
        wall(1, a.x.x - p_.lo.x, {1, 0, 0});
        wall(2, p_.hi.x - a.x.x, {-1, 0, 0});
        wall(3, a.x.z - p_.lo.z, {0, 0, 1});
        wall(4, p_.hi.z - a.x.z, {0, 0, -1});
      }
      // Particles j > i in the 27 neighbouring cells.
      int c[3];
      cellOf(a.x, c);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int cx = c[0] + dx, cy = c[1] + dy, cz = c[2] + dz;
            if (cx < 0 || cy < 0 || cz < 0 || cx >= nc_[0] || cy >= nc_[1] || cz >= nc_[2]) continue;
            const std::size_t cell = (std::size_t(cz) * nc_[1] + cy) * nc_[0] + cx;
            for (std::size_t k = start_[cell]; k < start_[cell + 1]; ++k) {
              const std::size_t j = order_[k];
              if (j <= i) continue;
              Particle& b = ps_[j];
              const Vec3 d = a.x - b.x;
              const double rs = a.r + b.r, d2 = dot(d, d);
              if (d2 >= rs * rs) continue;
              const double dist = std::sqrt(d2);
              if (dist <= 0) throw std::runtime_error("Dem: coincident particles");
              const Vec3 nrm = (1.0 / dist) * d;
              Vec3 xi;
              if (Vec3* h = findHistory(int(i), int(j))) xi = *h;
              const double meff = a.m * b.m / (a.m + b.m);
              contact(a, &b, nrm, rs - dist, a.r, b.r, meff, mu, xi);
              hist_[i].push_back({int(j), xi});
            }
          }
    }
    forcesValid_ = true;
  }

  void cellOf(Vec3 x, int c[3]) const {
    for (int d = 0; d < 3; ++d) {
      int k = int(std::floor((x[d] - org_[d]) / h_));
      c[d] = std::clamp(k, 0, nc_[d] - 1);
    }
  }

  // Counting sort of particles into cells (stable: index order within a cell).
  void buildCells() {
    double rmax = 0;
    Vec3 lo = ps_[0].x, hi = ps_[0].x;
    for (const auto& q : ps_) {
      rmax = std::max(rmax, q.r);
      for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], q.x[d]), hi[d] = std::max(hi[d], q.x[d]);
    }
    h_ = 2 * rmax * 1.0001;
    org_ = lo;
    long total = 1;
    for (int d = 0; d < 3; ++d) {
      nc_[d] = std::max(1, int(std::floor((hi[d] - lo[d]) / h_)) + 1);
      total *= nc_[d];
    }
    if (total > 50'000'000) throw std::runtime_error("Dem: particles spread over too many cells");
    start_.assign(std::size_t(total) + 1, 0);
    std::vector<std::size_t> cellIdx(ps_.size());
    for (std::size_t i = 0; i < ps_.size(); ++i) {
      int c[3];
      cellOf(ps_[i].x, c);
      cellIdx[i] = (std::size_t(c[2]) * nc_[1] + c[1]) * nc_[0] + c[0];
      ++start_[cellIdx[i] + 1];
    }
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    order_.resize(ps_.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < ps_.size(); ++i) order_[fill[cellIdx[i]]++] = i;
  }

  DemParams p_;
  double zeta_ = 0;
  std::vector<Particle> ps_;
  std::vector<std::vector<Contact>> hist_, histOld_;
  bool forcesValid_ = false;
  double time_ = 0;
  long steps_ = 0;
  double maxOverlap_ = 0;
  int nContacts_ = 0;
  // cell list
  Vec3 org_;
  double h_ = 1;
  int nc_[3] = {1, 1, 1};
  std::vector<std::size_t> start_, order_;
};

} // namespace pack
