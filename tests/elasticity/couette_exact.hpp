#pragma once
// Oscillatory Couette flow over an elastic layer: the periodic steady state of
// the linear problem (derivation: cases/elastic_couette/README.md).
//
//   0 < y < a  solid bonded to the fixed wall y = 0: density rhoS, shear modulus
//              G, optional Kelvin-Voigt viscosity etaS (Voigt's solid `viscosity`)
//   a < y < b  fluid: density rhoF, viscosity mu
//   y = b      wall moving as V sin(omega t) in x
//
// u(y, t) = Im[U(y) e^{i omega t}] with
//   solid  U = A sin(ks y),                            ks = omega sqrt(rhoS / Gc), Gc = G + i omega etaS
//   fluid  U = B cosh(kf (y - a)) + C sinh(kf (y - a)), kf = sqrt(i omega rhoF / mu)
//   B = A sin(ks a)                          (velocity continuous at y = a)
//   mu kf C = Gc ks cos(ks a) A / (i omega)  (shear stress continuous at y = a)
//   U(b) = V                                 (fixes A)
// Shear strain gamma = Im[U'(y) / (i omega) e^{i omega t}] (zero mean), elastic
// stress tau_S,xy = G gamma (Voigt's tau_S, whose rate is mu_S D with
// D = grad v + grad v^T, i.e. d tau_xy / dt = G du/dy).
#include <cmath>
#include <complex>

namespace voigt::test {

struct ElasticCouette {
  using cd = std::complex<double>;
  double rhoS, G, etaS, rhoF, mu, a, b, V, omega;
  cd ks, kf, A, B, C;

  ElasticCouette(double rhoS_, double G_, double etaS_, double rhoF_, double mu_, double a_, double b_, double V_,
                 double omega_)
      : rhoS(rhoS_), G(G_), etaS(etaS_), rhoF(rhoF_), mu(mu_), a(a_), b(b_), V(V_), omega(omega_) {
    const cd i(0, 1);
    const cd Gc = G + i * omega * etaS;
    ks = omega * std::sqrt(rhoS / Gc);
    kf = std::sqrt(i * omega * rhoF / mu);
    const cd cRatio = Gc * ks * std::cos(ks * a) / (i * omega * mu * kf); // C / A
    const cd bRatio = std::sin(ks * a);                                    // B / A
    const double L = b - a;
    A = V / (bRatio * std::cosh(kf * L) + cRatio * std::sinh(kf * L));
    B = bRatio * A;
    C = cRatio * A;
  }

  // Complex amplitudes of velocity and of du/dy.
  cd U(double y) const {
    if (y <= a) return A * std::sin(ks * y);
    return B * std::cosh(kf * (y - a)) + C * std::sinh(kf * (y - a));
  }
  cd dU(double y) const {
    if (y <= a) return A * ks * std::cos(ks * y);
    return kf * (B * std::sinh(kf * (y - a)) + C * std::cosh(kf * (y - a)));
  }

  cd phase(double t) const { return std::exp(cd(0, omega * t)); }
  double velocity(double y, double t) const { return std::imag(U(y) * phase(t)); }
  // Shear strain history du/dy integrated in time (zero mean); defined in the
  // fluid too, where it is what a solid stress field advected with the fluid
  // accumulates (the smoothed interface weights it by H).
  double strain(double y, double t) const { return std::imag(dU(y) / cd(0, omega) * phase(t)); }
  double elasticStress(double y, double t) const { return G * strain(y, t); }
  // Total shear stress tau_xy (continuous across y = a).
  double shearStress(double y, double t) const {
    if (y <= a) return std::imag((G + cd(0, omega * etaS)) * dU(y) / cd(0, omega) * phase(t));
    return std::imag(mu * dU(y) * phase(t));
  }
};

} // namespace voigt::test
