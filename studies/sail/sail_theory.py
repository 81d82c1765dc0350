#!/usr/bin/python3
"""Linear (thin-aerofoil) theory of a 2D extensible sail: the independent reference for the coupled case sail-2d.

A membrane of chord c (lengths below in units of c) is pinned at the leading edge x = 0 and the trailing edge
x = 1; the chord line is at incidence α to a uniform stream of dynamic pressure q = ½ρU²; z(x) is the membrane's
camber above the chord line. Assumptions: inviscid attached flow, thin aerofoil (small α, small slope z'),
steady, no membrane mass or bending stiffness; the tension T is uniform along the chord (no shear load).

  Aerodynamics (Glauert, x = (1 − cos θ)/2): the load ΔC_p = (p_lower − p_upper)/q on the camber line is
      ΔC_p(θ) = 4 [A_0 cot(θ/2) + Σ_{n≥1} A_n sin nθ],
      A_0 = α − (1/π) ∫_0^π z' dθ,   A_n = (2/π) ∫_0^π z' cos nθ dθ,
      C_L = π (2 A_0 + A_1),   C_m,LE = −(π/2)(A_0 + A_1 − A_2/2)  (nose up positive).
  Membrane (small slope, normal equilibrium):  C_T z'' = −ΔC_p,  z(0) = z(1) = 0,  C_T = T/(q c).
  Closure (extensible, linear elastic in the stretch):  C_T = C_T0 + Π ε,  Π = E t/(q c) (elasticity number),
      ε = (arc length − c)/c ≈ ½ ∫_0^1 z'² dx,  C_T0 = the pretension's tension coefficient (0: none; the
      unstretched length is then the chord).

Method (Nielsen's 1963 approach of solving for the load's Glauert coefficients): integrating the membrane
equation once gives the slope in closed form in terms of the load coefficients,
      C_T z'(θ) = w − [2A_0 (θ + sin θ) + A_1 (θ − ½ sin 2θ)
                       + Σ_{n≥2} A_n (sin(n−1)θ/(n−1) − sin(n+1)θ/(n+1))],   w = C_T z'(0),
and the Glauert projections of that slope are exact integrals, so the tangency conditions for A_0..A_N and
z(1) = 0 are N + 2 linear equations in (A_0..A_N, w) for a given C_T (Galerkin truncation at N terms; the only
error, algebraic in N because z'(θ) has a non-zero θ-derivative at θ = 0, π: the A_n fall off as 1/n²).
With α = 0 the same equations are the generalized eigenproblem whose eigenvalues are the tensions at which a
slack sail holds a cambered shape without incidence (Thwaites 1961); the physical branch of the extensible
sail has C_T above the first eigenvalue and is found by root finding on C_T − C_T0 − Π ε(C_T) = 0.

Usage:
  /usr/bin/python3 studies/sail/sail_theory.py --alpha 4 --elasticity 50 [--pretension 0] [--terms 128]
                                          [--json out.json] [--plot docs/img/sail_theory.png] [--table]
As a module: sys.path.insert(0, 'studies/sail'); import sail_theory; sail_theory.solve(4.0, 50.0) -> dict.
Bad input (negative Π, |α| > 15°, non-finite values, ...) exits 2 naming the argument."""
import argparse
import functools
import json
import math
import os
import sys

import numpy as np
from scipy import linalg, optimize

ALPHA_MAX_DEG = 15.0  # beyond this thin-aerofoil theory (attached flow, small slope) is not a reference
DEFAULT_TERMS = 128
SHAPE_POINTS = 41  # rows of the z(x) table (cosine spacing: fine near the edges)


class SailInputError(ValueError):
    """Input outside the theory's range; the message names the argument."""


# ----------------------------------------------------------------------------------------------------------
# The linear problem for a given tension coefficient
# ----------------------------------------------------------------------------------------------------------
def _sin_cos_projection(k, m):
    """∫_0^π sin kθ cos mθ dθ for integer arrays k ≥ 1, m ≥ 0."""
    k = np.asarray(k, dtype=float)
    m = np.asarray(m, dtype=float)
    odd = (np.rint(k + m).astype(int) % 2) == 1
    with np.errstate(divide="ignore", invalid="ignore"):
        val = np.where(odd, 2.0 * k / (k * k - m * m), 0.0)
    return val


def _theta_cos_projection(m):
    """∫_0^π θ cos mθ dθ for integer array m ≥ 0."""
    m = np.asarray(m, dtype=float)
    out = np.empty_like(m)
    zero = m == 0
    out[zero] = math.pi**2 / 2
    mm = m[~zero]
    out[~zero] = ((-1.0) ** mm - 1.0) / (mm * mm)
    return out


@functools.lru_cache(maxsize=16)
def _matrices(terms):
    """K, B of the Galerkin system (K + C_T B) u = C_T α e_0 for u = (A_0..A_N, w), N = terms.

    Rows 0..N: the tangency conditions multiplied by C_T,
      m = 0:  C_T A_0 + P_0[w − S] = C_T α,   m ≥ 1:  C_T A_m − P_m[w − S] = 0,
    with P_0 = (1/π)∫ dθ, P_m = (2/π)∫ cos mθ dθ and S the load's integral (module docstring).
    Row N + 1: z(1) = 0, i.e. ∫_0^π (w − S) sin θ dθ = 0 → 2w − 3πA_0 − πA_1 − (π/2)A_2 = 0."""
    n_a = terms + 1
    m = np.arange(n_a)
    weight = np.where(m == 0, 1.0 / math.pi, 2.0 / math.pi)
    # projections of the basis of S: columns n = 0..N, rows m = 0..N
    proj = np.zeros((n_a, n_a))
    th = _theta_cos_projection(m)
    proj[:, 0] = 2.0 * (th + _sin_cos_projection(1, m))
    if n_a > 1:
        proj[:, 1] = th - 0.5 * _sin_cos_projection(2, m)
    for n in range(2, n_a):
        proj[:, n] = _sin_cos_projection(n - 1, m) / (n - 1) - _sin_cos_projection(n + 1, m) / (n + 1)
    proj *= weight[:, None]
    p_one = np.where(m == 0, 1.0, 0.0)  # projections of the constant w
    sign = np.where(m == 0, 1.0, -1.0)  # m = 0 row has +P_0[w − S], the others −P_m[w − S]
    K = np.zeros((n_a + 1, n_a + 1))
    K[:n_a, :n_a] = -sign[:, None] * proj
    K[:n_a, n_a] = sign * p_one
    K[n_a, n_a] = 2.0
    K[n_a, 0] = -3.0 * math.pi
    if n_a > 1:
        K[n_a, 1] = -math.pi
    if n_a > 2:
        K[n_a, 2] = -0.5 * math.pi
    B = np.zeros_like(K)
    B[np.arange(n_a), np.arange(n_a)] = 1.0
    return K, B


def eigenvalues(terms=DEFAULT_TERMS):
    """Positive real tension coefficients C_T at which a sail at α = 0 holds a non-flat shape, largest first.
    They accumulate at 0 (a wavy membrane of wavenumber k is neutral at C_T ~ 4/k); the truncation resolves
    the largest ones only, the first (largest) is the one-bump mode of Thwaites' slack sail."""
    K, B = _matrices(terms)
    # K u = −C_T B u
    vals = linalg.eigvals(K, -B)
    vals = vals[np.isfinite(vals)]
    real = vals[np.abs(vals.imag) < 1e-9 * np.maximum(1.0, np.abs(vals.real))].real
    return np.sort(real[real > 0])[::-1]


@functools.lru_cache(maxsize=16)
def first_eigenvalue(terms=DEFAULT_TERMS):
    return float(eigenvalues(terms)[0])


def linear_solution(tension, alpha, terms=DEFAULT_TERMS):
    """Load coefficients A_0..A_N and w = C_T z'(0) for a given tension coefficient and α [rad]."""
    K, B = _matrices(terms)
    rhs = np.zeros(K.shape[0])
    rhs[0] = tension * alpha
    u = linalg.solve(K + tension * B, rhs)
    return u[:-1], u[-1]


def _slope_basis(theta, n_a):
    """Columns: the load-integral basis functions of S(θ) (module docstring) at the points theta."""
    th = np.asarray(theta, dtype=float)[:, None]
    n = np.arange(n_a)[None, :]
    cols = np.zeros((th.shape[0], n_a))
    cols[:, :1] = 2.0 * (th + np.sin(th))
    if n_a > 1:
        cols[:, 1:2] = th - 0.5 * np.sin(2 * th)
    if n_a > 2:
        nn = n[:, 2:]
        cols[:, 2:] = np.sin((nn - 1) * th) / (nn - 1) - np.sin((nn + 1) * th) / (nn + 1)
    return cols


def _j_integral(k, theta):
    """∫_0^θ sin kt sin t dt for integer array k ≥ 1 (columns) at points theta (rows)."""
    th = np.asarray(theta, dtype=float)[:, None]
    k = np.asarray(k, dtype=float)[None, :]
    one = k == 1
    km1 = np.where(one, 1.0, k - 1)
    general = 0.5 * (np.sin((k - 1) * th) / km1 - np.sin((k + 1) * th) / (k + 1))
    special = th / 2 - np.sin(2 * th) / 4
    return np.where(one, special, general)


def _shape_basis(theta, n_a):
    """∫_0^θ (basis of S) sin t dt, columns as _slope_basis."""
    th = np.asarray(theta, dtype=float)
    t_sin = np.sin(th) - th * np.cos(th)  # ∫ t sin t
    cols = np.zeros((th.shape[0], n_a))
    cols[:, 0] = 2.0 * (t_sin + _j_integral([1], th)[:, 0])
    if n_a > 1:
        cols[:, 1] = t_sin - 0.5 * _j_integral([2], th)[:, 0]
    if n_a > 2:
        n = np.arange(2, n_a)
        cols[:, 2:] = _j_integral(n - 1, th) / (n - 1) - _j_integral(n + 1, th) / (n + 1)
    return cols


def slope(theta, A, w, tension):
    """z'(θ)."""
    return (w - _slope_basis(theta, len(A)) @ A) / tension


def camber(theta, A, w, tension):
    """z(θ) = ½ ∫_0^θ z' sin t dt (exact for the truncated series)."""
    th = np.asarray(theta, dtype=float)
    return 0.5 * (w * (1 - np.cos(th)) - _shape_basis(th, len(A)) @ A) / tension


@functools.lru_cache(maxsize=16)
def _gauss(points):
    x, wq = np.polynomial.legendre.leggauss(points)
    return 0.5 * math.pi * (x + 1), 0.5 * math.pi * wq


def strain(A, w, tension):
    """ε = ½ ∫_0^1 z'² dx = ¼ ∫_0^π z'(θ)² sin θ dθ (Gauss–Legendre; smooth in θ)."""
    th, wq = _gauss(max(96, 4 * len(A)))
    zp = slope(th, A, w, tension)
    return 0.25 * float(np.sum(wq * zp * zp * np.sin(th)))


def coefficients(A):
    """C_L and C_m about the leading edge from the load coefficients."""
    a = np.zeros(3)
    a[: min(3, len(A))] = A[:3]
    return math.pi * (2 * a[0] + a[1]), -0.5 * math.pi * (a[0] + a[1] - 0.5 * a[2])


def max_camber(A, w, tension):
    """(z_max, x at z_max): the extreme of z with the sign of the camber (positive for α > 0)."""
    th = np.linspace(0.0, math.pi, 801)
    z = camber(th, A, w, tension)
    sgn = 1.0 if abs(z.max()) >= abs(z.min()) else -1.0
    i = int(np.argmax(sgn * z))
    lo, hi = th[max(i - 1, 0)], th[min(i + 1, len(th) - 1)]
    res = optimize.minimize_scalar(lambda t: -sgn * camber(np.array([t]), A, w, tension)[0], bounds=(lo, hi),
                                   method="bounded", options={"xatol": 1e-12})
    t = float(res.x)
    return float(camber(np.array([t]), A, w, tension)[0]), 0.5 * (1 - math.cos(t))


# ----------------------------------------------------------------------------------------------------------
# The extensible sail
# ----------------------------------------------------------------------------------------------------------
def _check(name, value, low=None, high=None, what=""):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise SailInputError(f"{name}: not a number: {value!r}") from None
    if not math.isfinite(v):
        raise SailInputError(f"{name}: must be finite, got {value!r}")
    if low is not None and v < low:
        raise SailInputError(f"{name}: must be >= {low:g}{what}, got {v:g}")
    if high is not None and abs(v) > high:
        raise SailInputError(f"{name}: |value| must be <= {high:g}{what}, got {v:g}")
    return v


def solve_tension(alpha_deg, elasticity, pretension=0.0, terms=DEFAULT_TERMS):
    """The tension coefficient of the equilibrium on the physical branch (C_T above the first eigenvalue)."""
    alpha = math.radians(alpha_deg)
    lam1 = first_eigenvalue(terms)

    def strain_per_alpha2(ct):
        A, w = linear_solution(ct, 1.0, terms)
        return strain(A, w, ct)

    if alpha == 0.0 or elasticity == 0.0:
        return pretension
    # g(C_T) = C_T − C_T0 − Π α² e(C_T): −∞ at the eigenvalue (the camber of the linear problem diverges
    # there), +∞ for large C_T; e(C_T) falls monotonically on (λ_1, ∞), so the root is unique.
    def g(ct):
        return ct - pretension - elasticity * alpha * alpha * strain_per_alpha2(ct)

    lo = max(lam1 * (1 + 1e-10), pretension)
    if g(lo) >= 0:  # only with pretension: already taut enough
        return lo
    # large-C_T asymptote: e ≈ e_1/C_T² → C_T ≈ C_T0 + (Π α² e_1)^(1/3); start above it and widen
    hi = max(2 * lo, pretension + 2 * (elasticity * alpha * alpha * 1.0) ** (1 / 3) + 1.0)
    while g(hi) <= 0:
        hi *= 2
    return optimize.brentq(g, lo, hi, xtol=1e-14 * hi, rtol=1e-14, maxiter=200)


def solve(alpha_deg, elasticity, pretension=0.0, terms=DEFAULT_TERMS, shape_points=SHAPE_POINTS):
    """Equilibrium of the extensible sail. alpha_deg: incidence of the chord [deg]; elasticity: Π = E t/(q c);
    pretension: C_T0 = T_0/(q c). Returns C_L, C_T, C_m_le (about the leading edge, nose up positive),
    camber_max (z_max/c), x_camber_max (x/c), strain ε, first_eigenvalue, shape [[x/c, z/c], ...] and the inputs.
    Raises SailInputError (a ValueError) naming the argument for input outside the theory."""
    alpha_deg = _check("alpha", alpha_deg, high=ALPHA_MAX_DEG, what=" degrees (thin-aerofoil theory)")
    elasticity = _check("elasticity", elasticity, low=0.0)
    pretension = _check("pretension", pretension, low=0.0)
    if not isinstance(terms, int) or terms < 4:
        raise SailInputError(f"terms: must be an integer >= 4, got {terms!r}")
    lam1 = first_eigenvalue(terms)
    if elasticity == 0.0 and pretension <= lam1 and alpha_deg != 0.0:
        raise SailInputError(f"elasticity: 0 needs a pretension above the first eigenvalue {lam1:.6g} "
                             f"(an inextensible sail with less tension has no steady state), got pretension "
                             f"{pretension:g}")
    ct = solve_tension(alpha_deg, elasticity, pretension, terms)
    alpha = math.radians(alpha_deg)
    if alpha == 0.0 or ct == 0.0:
        A, w, ct_eval = np.zeros(terms + 1), 0.0, 1.0
        A[0] = alpha
    else:
        A, w = linear_solution(ct, alpha, terms)
        ct_eval = ct
    c_l, c_m = coefficients(A)
    z_max, x_max = max_camber(A, w, ct_eval) if alpha != 0.0 else (0.0, 0.5)
    th = np.linspace(0.0, math.pi, shape_points)
    x = 0.5 * (1 - np.cos(th))
    z = camber(th, A, w, ct_eval)
    z[0] = 0.0
    return {
        "alpha_deg": alpha_deg, "elasticity": elasticity, "pretension": pretension, "terms": terms,
        "C_L": c_l + 0.0, "C_L_flat_plate": 2 * math.pi * alpha, "C_T": ct, "C_m_le": c_m + 0.0,
        "camber_max": z_max, "x_camber_max": x_max, "strain": strain(A, w, ct_eval),
        "first_eigenvalue": lam1, "load_coefficients": [float(a) for a in A[:8]],
        "shape": [[float(a), float(b)] for a, b in zip(x, z)],
    }


def elasticity_for_camber(alpha_deg, camber_target, pretension=0.0, terms=DEFAULT_TERMS):
    """Π that gives the maximum camber camber_target (z_max/c) at incidence alpha_deg."""
    def miss(log_pi):
        return solve(alpha_deg, math.exp(log_pi), pretension, terms, shape_points=2)["camber_max"] - camber_target
    return math.exp(optimize.brentq(miss, math.log(1e-3), math.log(1e8), xtol=1e-12))


# ----------------------------------------------------------------------------------------------------------
# Command line
# ----------------------------------------------------------------------------------------------------------
TABLE_ELASTICITIES = (5, 10, 20, 50, 100, 200, 500, 1000)
# The proposed sail-2d set-up (docs/SAIL_THEORY.md): 4.4 % camber at α = 4°; with U = 1 m/s, ρ = 1 kg/m³,
# c = 1 m (q = 0.5 Pa) that is E t = Π q c = 250 N/m.
PROPOSED_ELASTICITY = 500.0


def table(alpha_deg=4.0, elasticities=TABLE_ELASTICITIES, terms=DEFAULT_TERMS):
    rows = []
    for e in elasticities:
        r = solve(alpha_deg, e, 0.0, terms, shape_points=2)
        rows.append((e, r["C_L"], r["C_L"] / r["C_L_flat_plate"], r["C_T"], r["camber_max"], r["x_camber_max"],
                     r["C_m_le"]))
    return rows


def plot(path, alpha_deg=4.0, terms=DEFAULT_TERMS):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    pis = np.geomspace(2.0, 1e4, 60)
    res = [solve(alpha_deg, p, 0.0, terms, shape_points=2) for p in pis]
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(14, 4.2))
    ax1.semilogx(pis, [r["C_L"] for r in res], label="extensible sail")
    ax1.axhline(2 * math.pi * math.radians(alpha_deg), color="k", ls="--", lw=0.8, label="flat plate 2πα")
    ax1.set_xlabel("elasticity number Π = E t / (q c)")
    ax1.set_ylabel("C_L")
    for ax in (ax1, ax2):
        ax.axvline(PROPOSED_ELASTICITY, color="grey", ls=":", lw=1.0)
    ax1.text(PROPOSED_ELASTICITY * 1.1, 0.5 * ax1.get_ylim()[1], f"sail-2d:\nΠ = {PROPOSED_ELASTICITY:g}", fontsize=8)
    ax1.legend()
    ax1.grid(True, which="both", lw=0.3)
    ax2.loglog(pis, [r["camber_max"] for r in res], label="z_max / c")
    ax2.loglog(pis, [r["C_T"] for r in res], label="C_T = T/(q c)")
    ax2.set_xlabel("elasticity number Π")
    ax2.legend()
    ax2.grid(True, which="both", lw=0.3)
    for p in (5, 20, 100, PROPOSED_ELASTICITY):
        r = solve(alpha_deg, p, 0.0, terms, shape_points=101)
        s = np.array(r["shape"])
        ax3.plot(s[:, 0], s[:, 1], label=f"Π = {p:g}")
    ax3.set_xlabel("x / c")
    ax3.set_ylabel("z / c (above the chord)")
    ax3.legend()
    ax3.grid(True, lw=0.3)
    fig.suptitle(f"Linear theory of a 2D extensible sail, α = {alpha_deg:g}°, no pretension (studies/sail/sail_theory.py)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _finite_float(name):
    def parse(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
        return v
    return parse


def main(argv=None):
    ap = argparse.ArgumentParser(description="Linear theory of a 2D extensible sail (thin aerofoil + membrane).")
    ap.add_argument("--alpha", type=_finite_float("--alpha"), default=4.0, help="incidence [deg], |α| <= 15")
    ap.add_argument("--elasticity", type=_finite_float("--elasticity"), default=None,
                    help="Π = E t/(q c) (required unless --table or --plot only)")
    ap.add_argument("--pretension", type=_finite_float("--pretension"), default=0.0, help="C_T0 = T_0/(q c)")
    ap.add_argument("--terms", type=int, default=DEFAULT_TERMS, help="Glauert terms N (default %(default)s)")
    ap.add_argument("--json", help="write the result to this file")
    ap.add_argument("--plot", help="PNG: C_L, camber, C_T against Π and shapes at --alpha")
    ap.add_argument("--table", action="store_true", help="print C_L, camber against Π at --alpha (Markdown)")
    args = ap.parse_args(argv)
    if args.elasticity is None and not (args.table or args.plot):
        ap.error("--elasticity: required")
    try:
        if args.elasticity is not None:
            r = solve(args.alpha, args.elasticity, args.pretension, args.terms)
            print(f"alpha = {r['alpha_deg']:g} deg, elasticity Pi = {r['elasticity']:g}, pretension C_T0 = "
                  f"{r['pretension']:g}, N = {r['terms']}")
            print(f"C_L      = {r['C_L']:.6f}   (flat plate 2*pi*alpha = {r['C_L_flat_plate']:.6f})")
            print(f"C_T      = {r['C_T']:.6f}   (T/(q c); first eigenvalue of the slack sail "
                  f"{r['first_eigenvalue']:.6f})")
            print(f"C_m,LE   = {r['C_m_le']:.6f}   (nose up positive)")
            print(f"z_max/c  = {r['camber_max']:.6f} at x/c = {r['x_camber_max']:.4f}")
            print(f"strain   = {r['strain']:.6e}")
            print("      x/c         z/c")
            for x, z in r["shape"]:
                print(f"  {x:9.6f}  {z:10.7f}")
            if args.json:
                with open(args.json, "w") as f:
                    json.dump(r, f, indent=1)
        else:
            _check("alpha", args.alpha, high=ALPHA_MAX_DEG, what=" degrees (thin-aerofoil theory)")
        if args.table:
            print(f"\n| Π | C_L | C_L/(2πα) | C_T | z_max/c | x/c at z_max | C_m,LE |   (α = {args.alpha:g}°)")
            print("|---|---|---|---|---|---|---|")
            for e, cl, ratio, ct, zm, xm, cm in table(args.alpha, terms=args.terms):
                print(f"| {e:g} | {cl:.4f} | {ratio:.3f} | {ct:.4f} | {zm:.4f} | {xm:.3f} | {cm:.4f} |")
        if args.plot:
            plot(args.plot, args.alpha, args.terms)
    except SailInputError as e:
        print(f"sail_theory.py: error: --{e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # output cut short by the reader (e.g. `| head`): not an error of the theory
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        sys.exit(0)
