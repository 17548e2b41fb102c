// Gravity deposition of spheres in a duct (DEM, dem.hpp) and the measurements on the result:
// surface height, voidage (exact sphere-box volumes, geometry.hpp), coordination, bonding.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "dem.hpp"
#include "geometry.hpp"

namespace pack {

struct PackConfig {
  Vec3 duct{0.11, 0.33, 0.11}; // m; x, y (vertical, gravity -y), z; the duct's lower corner is the origin
  double diameter = 0.025;     // mean sphere diameter, m
  double polydispersity = 0;   // diameters uniform in d (1 +- p)
  double base = 0.05;          // y of the support plane the bed is poured onto
  double bedTop = 0.29;        // target surface height (used when count == 0)
  int count = 0;               // number of spheres; 0: pour until the surface reaches bedTop
  int batch = 0;               // spheres per pour; 0: about one layer
  std::uint64_t seed = 1;
  double restitution = 0.6;
  double friction = 0.5;
  double wallFriction = 0.5;
  double density = 10;          // kg/m^3 (paper's solid; the geometry depends only on ratios)
  double stiffnessRatio = 1e5;  // k_n d / (m g): weight of one sphere compresses a contact by d/ratio
  double dtFraction = 1.0 / 50; // dt / t_c (t_c: binary contact time of the two lightest spheres)
  double keTol = 1e-8;          // settled: kinetic energy per sphere < keTol * m g d
  double batchKeTol = 1e-4;     // between pours
  double maxTime = 30;          // cap on simulated time, s
  double cloudFraction = 0.2;   // solid fraction of the random cloud a pour starts from
  double inflate = 0.01;        // output radii = (1 + inflate) * DEM radii
  double holdWidth = 0.011;     // the scene's zero-velocity layer along the side walls
  double clearance = 0.02;      // spheres reaching within this distance of the duct top are removed
  std::function<void(const std::string&)> log;
};

struct Sphere {
  double x, y, z, r;
};

// Portable uniform [0, 1) from mt19937_64 (whose sequence the standard fixes).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  double uniform() { return double(g_() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

 private:
  std::mt19937_64 g_;
};

struct PackResult {
  std::vector<Sphere> dem;    // as settled (DEM radii)
  std::vector<Sphere> output; // radii inflated
  double simTime = 0, dt = 0, contactTime = 0, kn = 0, mg = 0;
  long steps = 0;
  int pours = 0;
  int trimmed = 0; // spheres removed for the clearance below the duct top
  bool settled = false;
  double finalKe = 0; // per sphere, in units of m g d
  double maxOverlap = 0;
};

inline double meanSphereVolume(const PackConfig& c) {
  // E[d^3] for d uniform in d0 (1 +- p): d0^3 (1 + p^2)
  const double d = c.diameter, p = c.polydispersity;
  return kPi / 6 * d * d * d * (1 + p * p);
}

inline std::vector<Sphere> spheresOf(const Dem& dem) {
  std::vector<Sphere> s;
  for (const auto& q : dem.particles()) s.push_back({q.x.x, q.x.y, q.x.z, q.r});
  return s;
}

// Mean surface height: the duct's cross-section split into round(L/d) columns per direction;
// in each, the highest sphere top (y + r) among spheres centred in it; the mean over columns.
inline double surfaceHeight(const std::vector<Sphere>& s, const PackConfig& c) {
  const int nx = std::max(1, int(std::lround(c.duct.x / c.diameter)));
  const int nz = std::max(1, int(std::lround(c.duct.z / c.diameter)));
  std::vector<double> peak(std::size_t(nx) * nz, c.base);
  for (const auto& q : s) {
    const int i = std::clamp(int(q.x / c.duct.x * nx), 0, nx - 1), k = std::clamp(int(q.z / c.duct.z * nz), 0, nz - 1);
    double& p = peak[std::size_t(k) * nx + i];
    p = std::max(p, q.y + q.r);
  }
  return std::accumulate(peak.begin(), peak.end(), 0.0) / double(peak.size());
}

inline double solidVolume(const std::vector<Sphere>& s, const Box& b) {
  double v = 0;
  for (const auto& q : s) {
    const double c[3] = {q.x, q.y, q.z};
    v += sphereBoxVolume(c, q.r, b);
  }
  return v;
}

inline double voidage(const std::vector<Sphere>& s, const Box& b) {
  const double vol = (b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]);
  return vol > 0 ? 1 - solidVolume(s, b) / vol : std::nan("");
}

inline Box ductSlab(const PackConfig& c, double y0, double y1, double wall = 0) {
  return Box{{wall, y0, wall}, {c.duct.x - wall, y1, c.duct.z - wall}};
}

// Inserts n spheres at random non-overlapping positions in a cloud above everything present.
inline void pourCloud(Dem& dem, int n, const PackConfig& c, Rng& rng) {
  double ybot = c.base;
  for (const auto& q : dem.particles()) ybot = std::max(ybot, q.x.y + q.r);
  ybot += 0.25 * c.diameter;
  const double area = c.duct.x * c.duct.z;
  double height = std::max(c.diameter * (1 + c.polydispersity), n * meanSphereVolume(c) / (area * c.cloudFraction));
  std::vector<Sphere> placed;
  for (int k = 0; k < n; ++k) {
    const double r = 0.5 * c.diameter * (1 + c.polydispersity * (2 * rng.uniform() - 1));
    for (int attempt = 0;; ++attempt) {
      if (attempt > 0 && attempt % 2000 == 0) height *= 1.2; // crowded: make the cloud taller
      const Sphere s{rng.uniform(r, c.duct.x - r), ybot + r + rng.uniform() * height, rng.uniform(r, c.duct.z - r), r};
      bool ok = true;
      for (const auto& o : placed) {
        const double dx = s.x - o.x, dy = s.y - o.y, dz = s.z - o.z, rs = s.r + o.r;
        if (dx * dx + dy * dy + dz * dz < rs * rs) {
          ok = false;
          break;
        }
      }
      if (ok) {
        placed.push_back(s);
        break;
      }
    }
  }
  for (const auto& s : placed) dem.add({s.x, s.y, s.z}, s.r);
}

// Runs until the kinetic energy per sphere is below tol (J), but not before minTime has passed.
inline bool settle(Dem& dem, double tol, double minTime, double maxTime) {
  const double t0 = dem.time();
  for (;;) {
    for (int k = 0; k < 200; ++k) dem.step();
    const double t = dem.time() - t0;
    if (t >= minTime && dem.kineticEnergyPerParticle() < tol) return true;
    if (dem.time() >= maxTime) return false;
  }
}

inline PackResult deposit(const PackConfig& c) {
  if (!(c.diameter > 0) || c.polydispersity < 0 || c.polydispersity >= 1)
    throw std::invalid_argument("diameter must be > 0 and polydispersity in [0, 1)");
  if (c.duct.x < c.diameter * (1 + c.polydispersity) || c.duct.z < c.diameter * (1 + c.polydispersity))
    throw std::invalid_argument("duct narrower than a sphere");
  if (c.count <= 0 && !(c.bedTop > c.base)) throw std::invalid_argument("bed top must be above the base");
  auto log = [&](const std::string& s) {
    if (c.log) c.log(s);
  };
  const double d = c.diameter, vs = meanSphereVolume(c), area = c.duct.x * c.duct.z;
  const double m = c.density * kPi / 6 * d * d * d, mg = m * 9.81;
  DemParams p;
  p.density = c.density;
  p.kn = c.stiffnessRatio * mg / d;
  p.restitution = c.restitution;
  p.friction = c.friction;
  p.wallFriction = c.wallFriction;
  p.lo = {0, c.base, 0};
  p.hi = {c.duct.x, c.duct.y, c.duct.z};
  Dem dem(p);
  Rng rng(c.seed);
  const int layer = std::max(1, int(std::lround(area * d * 0.6 / vs)));
  const int batch = c.batch > 0 ? c.batch : layer;
  PackResult res;
  res.kn = p.kn;
  res.mg = mg;
  double phi = 0.6; // solid fraction estimate, updated from the bed
  char buf[256];
  for (int pour = 0;; ++pour) {
    int n = 0;
    const int have = int(dem.particles().size());
    if (c.count > 0) {
      n = std::min(batch, c.count - have);
    } else {
      const auto s = spheresOf(dem);
      const double h = have ? surfaceHeight(s, c) : c.base;
      if (h > c.base + 2 * d) phi = 1 - voidage(s, ductSlab(c, c.base + 0.5 * d, h - 0.5 * d));
      const double missing = area * (c.bedTop - h) * phi / vs;
      if (missing >= 0.5) n = std::min(batch, std::max(1, int(std::lround(missing))));
      std::snprintf(buf, sizeof buf, "pour %d: N = %d, surface %.4f m, solid fraction %.3f, adding %d", pour, have,
                    h, phi, n);
      log(buf);
    }
    if (n <= 0) break;
    if (pour > 200) throw std::runtime_error("deposition did not converge to the bed height");
    pourCloud(dem, n, c, rng);
    if (pour == 0) dem.setTimeStep(c.dtFraction);
    double ytop = c.base;
    for (const auto& q : dem.particles()) ytop = std::max(ytop, q.x.y + q.r);
    const double fall = std::sqrt(2 * (ytop - c.base) / p.gravity);
    const bool ok = settle(dem, c.batchKeTol * mg * d, 1.2 * fall + 0.05, c.maxTime);
    ++res.pours;
    if (!ok) {
      log("warning: maximum simulated time reached while pouring");
      break;
    }
  }
  res.settled = settle(dem, c.keTol * mg * d, 0.05, c.maxTime);
  // A sphere left perched on the surface may reach the outlet: remove such spheres, settle again.
  std::vector<bool> drop;
  for (const auto& q : dem.particles()) drop.push_back(q.x.y + q.r > c.duct.y - c.clearance);
  res.trimmed = int(std::count(drop.begin(), drop.end(), true));
  if (res.trimmed > 0) {
    std::snprintf(buf, sizeof buf, "removing %d sphere(s) above y = %.4f m", res.trimmed, c.duct.y - c.clearance);
    log(buf);
    dem.remove(drop);
    res.settled = settle(dem, c.keTol * mg * d, 0.05, c.maxTime);
  }
  std::snprintf(buf, sizeof buf, "settled=%d after %.3f s simulated, %ld steps (dt %.3g s)", int(res.settled),
                dem.time(), dem.steps(), dem.params().dt);
  log(buf);
  res.simTime = dem.time();
  res.steps = dem.steps();
  res.dt = dem.params().dt;
  res.contactTime = dem.contactTime();
  res.finalKe = dem.kineticEnergyPerParticle() / (mg * d);
  res.maxOverlap = dem.maxOverlap();
  res.dem = spheresOf(dem);
  res.output = res.dem;
  for (auto& s : res.output) s.r *= 1 + c.inflate;
  return res;
}

// ---------------------------------------------------------------------------------------------
// Contacts, coordination and bonding.

struct ContactStats {
  int n = 0;
  int pairs = 0;          // sphere-sphere contacts (gap < tol)
  int wallContacts = 0;   // sphere-wall (and floor) contacts
  double z = 0;           // mean sphere-sphere coordination, 2 pairs / N
  double zWalls = 0;      // including walls and floor
  int rattlers = 0;       // spheres with no sphere-sphere contact
  double overlapMean = 0, overlapMin = 0, overlapMax = 0; // over pairs, in units of the mean diameter
  int components = 0;     // connected groups of spheres (pairs as edges)
  int largest = 0;
  int unanchored = 0;     // spheres in groups that reach no side-wall hold layer
  std::vector<int> histogram; // count of spheres by sphere-sphere contact number
};

inline ContactStats contacts(const std::vector<Sphere>& s, const PackConfig& c, double tol) {
  ContactStats st;
  const int n = int(s.size());
  st.n = n;
  std::vector<int> deg(n, 0), parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  double sum = 0;
  st.overlapMin = 1e300;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double dx = s[i].x - s[j].x, dy = s[i].y - s[j].y, dz = s[i].z - s[j].z;
      const double gap = std::sqrt(dx * dx + dy * dy + dz * dz) - s[i].r - s[j].r;
      if (gap >= tol) continue;
      ++st.pairs;
      ++deg[i], ++deg[j];
      const double ov = -gap / c.diameter;
      sum += ov;
      st.overlapMin = std::min(st.overlapMin, ov);
      st.overlapMax = std::max(st.overlapMax, ov);
      parent[find(i)] = find(j);
    }
  if (st.pairs == 0) st.overlapMin = 0;
  st.overlapMean = st.pairs ? sum / st.pairs : 0;
  std::vector<char> anchored(n, 0);
  for (int i = 0; i < n; ++i) {
    const auto& q = s[i];
    if (q.y - q.r < c.base + tol) ++st.wallContacts;
    for (double dist : {q.x, c.duct.x - q.x, q.z, c.duct.z - q.z})
      if (dist - q.r < tol) ++st.wallContacts;
    if (q.x - q.r < c.holdWidth || q.x + q.r > c.duct.x - c.holdWidth || q.z - q.r < c.holdWidth ||
        q.z + q.r > c.duct.z - c.holdWidth)
      anchored[find(i)] = 1;
  }
  std::vector<int> size(n, 0);
  for (int i = 0; i < n; ++i) ++size[find(i)];
  for (int i = 0; i < n; ++i) {
    if (find(i) == i) ++st.components, st.largest = std::max(st.largest, size[i]);
    if (!anchored[find(i)]) ++st.unanchored;
    if (deg[i] == 0) ++st.rattlers;
    if (int(st.histogram.size()) <= deg[i]) st.histogram.resize(deg[i] + 1, 0);
    ++st.histogram[deg[i]];
  }
  st.z = n ? 2.0 * st.pairs / n : 0;
  st.zWalls = n ? (2.0 * st.pairs + st.wallContacts) / n : 0;
  return st;
}

// Ergun (1952), Chem. Eng. Prog. 48, 89-94; the paper's Eq. (23):
// dp/dy = (1 - e)/e^3 rho U^2 / d (150 (1 - e) mu / (d U rho) + 1.75), U superficial velocity.
inline double ergun(double eps, double u, double rho, double mu, double d) {
  return (1 - eps) / (eps * eps * eps) * rho * u * u / d * (150 * (1 - eps) * mu / (d * u * rho) + 1.75);
}

// CSV that the level-set shape sphere_packing reads: header x,y,z,r then one sphere per line (m).
inline std::string toCsv(const std::vector<Sphere>& s) {
  std::string out = "x,y,z,r\n";
  char buf[128];
  for (const auto& q : s) {
    std::snprintf(buf, sizeof buf, "%.7f,%.7f,%.7f,%.7f\n", q.x, q.y, q.z, q.r);
    out += buf;
  }
  return out;
}

} // namespace pack
