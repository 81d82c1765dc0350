#!/usr/bin/env python3
"""The Hencky problem's exact answer for this solver's continuum model, to many digits: a clamped circular
membrane (radius a, E t = Y, Poisson ν) under a uniform follower pressure p, Green–Lagrange strain, St
Venant–Kirchhoff plane stress on the reference thickness. The published value (33.14 mm for the case's data,
docs/VALIDATION.md) has 4 digits; mesh-convergence errors below 1e-4 need more (studies/cost/accuracy_cost.py).

Axisymmetric equilibrium on the reference radius R, deformed meridian x(R) = (r, z):
    d/dR (R S_r x') − S_θ (r/R) e_r + p r n = 0,   n = (−z', r')
with stretches λ_r = |x'|, λ_θ = r/R, E = (λ² − 1)/2 and resultants S_r = Y/(1−ν²) (E_r + ν E_θ), S_θ
likewise.
With q = R S_r x' the system (r, z, q) is first order; at the centre the stretch λ₀ is isotropic and the
surface a paraboloid of curvature p / (2 S₀) (Young–Laplace). Shooting on λ₀ until r(a) = a (RK4, then a
secant iteration); the answer is checked by halving the step.
Usage: studies/common/hencky_reference.py   (prints the centre deflection of cases/structure/hencky)"""
import math


def _rhs(R, y, C, nu, p, lam_guess):
    r, _, qr, qz = y
    et = ((r / R) ** 2 - 1) / 2
    # |q| = R λ_r C ((λ_r² − 1)/2 + ν E_θ): a cubic in λ_r, increasing where the membrane is taut; Newton.
    qn = math.hypot(qr, qz) / (R * C)
    lam = lam_guess[0]
    for _ in range(50):
        f = lam * ((lam * lam - 1) / 2 + nu * et) - qn
        step = f / (1.5 * lam * lam - 0.5 + nu * et)
        lam -= step
        if abs(step) < 1e-15 * lam:
            break
    lam_guess[0] = lam
    sr = C * ((lam * lam - 1) / 2 + nu * et)
    st = C * (et + nu * (lam * lam - 1) / 2)
    rp, zp = qr / (R * sr), qz / (R * sr)
    return (rp, zp, st * r / R + p * r * zp, -p * r * rp)


def _shoot(lam0, a, Y, nu, p, steps):
    """Integrates from the centre with the isotropic stretch lam0; returns (r(a), z(a)) with z(0) = 0."""
    C = Y / (1 - nu * nu)
    s0 = C * (1 + nu) * (lam0 * lam0 - 1) / 2
    c = p / (2 * s0)
    R = 1e-9 * a
    y = (lam0 * R, -c * (lam0 * R) ** 2 / 2, R * s0 * lam0, -R * s0 * c * lam0 * lam0 * R)
    h = (a - R) / steps
    guess = [lam0]
    for _ in range(steps):
        k1 = _rhs(R, y, C, nu, p, guess)
        k2 = _rhs(R + h / 2, tuple(v + h / 2 * k for v, k in zip(y, k1)), C, nu, p, guess)
        k3 = _rhs(R + h / 2, tuple(v + h / 2 * k for v, k in zip(y, k2)), C, nu, p, guess)
        k4 = _rhs(R + h, tuple(v + h * k for v, k in zip(y, k3)), C, nu, p, guess)
        y = tuple(v + h / 6 * (d1 + 2 * d2 + 2 * d3 + d4) for v, d1, d2, d3, d4 in zip(y, k1, k2, k3, k4))
        R += h
    return y[0], y[1]


def centre_deflection(a=0.1425, Y=311488.0, nu=0.34, p=100.0e3, steps=4000):
    """Centre deflection [m] (defaults: cases/structure/hencky)."""
    def miss(l0):
        return _shoot(l0, a, Y, nu, p, steps)[0] - a
    l0, l1 = 1.01, 1.05
    f0, f1 = miss(l0), miss(l1)
    for _ in range(60):  # secant on the rim radius
        l2 = l1 - f1 * (l1 - l0) / (f1 - f0)
        l0, f0, l1 = l1, f1, l2
        f1 = miss(l1)
        if abs(f1) < 1e-15 * a:
            break
    return -_shoot(l1, a, Y, nu, p, steps)[1]


if __name__ == "__main__":
    w, w2 = centre_deflection(steps=2000), centre_deflection(steps=4000)
    print(f"centre deflection {w2 * 1e3:.9f} mm (2000 RK4 steps: {w * 1e3:.9f} mm)")
