#!/usr/bin/python3
"""Reference values for the drag closures of src/coupling/drag/, written INDEPENDENTLY of the C++
from the published formulas (plain math with mpmath at 50 digits), to tests/models/drag/*.toml.

Run:  /usr/bin/python3 tools/drag_reference.py        (rewrites tests/models/drag/*.toml)

Each closure below is coded in the form its source prints it (beta, or the force on one particle),
not in the K = beta/(1 - eps) form the C++ uses. Conventions (docs/drag.md):
  beta  : force per unit mixture volume = beta (u - v)                [Deen07 eq. 1-2]
  F_p   = V_p beta / (1 - eps) |u - v|   (drag part, Model A)
  F     = F_p / (3 pi mu d eps |u - v|)  (normalised on the superficial slip velocity)
  Re_p  = eps rho |u - v| d / mu
The single-particle cases (eps = 1) have beta = 0 exactly; their F is the limit, evaluated here
at eps = 1 - 1e-30 (the difference is far below the 1e-9 tolerance), which checks the C++ limit
handling independently.
"""
import os

from mpmath import mp, mpf, pi, sqrt, log, log10, exp, findroot

mp.dps = 50

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "models", "drag")

TINY = mpf("1e-30")  # eps = 1 - TINY stands for the single-particle limit


def cd_sn(re):
    """Schiller-Naumann [Deen07 eq. 4, Hoomans96 eq. 38]."""
    return 24 / re * (1 + mpf("0.15") * re ** mpf("0.687")) if re < 1000 else mpf("0.44")


def re_p(eps, rho, slip, d, mu):
    return eps * rho * slip * d / mu


def vp(d):
    return pi * d ** 3 / 6


# Branch thresholds are compared with the DOUBLE nearest to the printed constant (mpf(0.8), not
# mpf("0.8")), as the C++ does, so that a case sitting exactly on a threshold (eps = 0.8, 0.6)
# takes the same branch in both.

# ---- closures, as published --------------------------------------------------------------


def ergun(eps, d, mu, rho, slip, **_):
    """[Hoomans96 eq. 45] beta = 150 (1-e)^2 mu/(e d^2) + 1.75 (1-e) rho |u-v| / d."""
    es = 1 - eps
    return 150 * es ** 2 * mu / (eps * d ** 2) + mpf("1.75") * es * rho * slip / d


def wen_yu(eps, d, mu, rho, slip, **_):
    """[Hoomans96 eq. 46] beta = 3/4 C_d e (1-e) rho |u-v| / d * e^-2.65, Re_p = e rho|u-v|d/mu."""
    re = re_p(eps, rho, slip, d, mu)
    return mpf(3) / 4 * cd_sn(re) * eps * (1 - eps) * rho * slip / d * eps ** mpf("-2.65")


def wen_yu_single(eps, d, mu, rho, slip, **_):
    """[Hoomans96 eq. 35-39] F_d = pi/8 d^2 C_d' rho |v| v, v = e (u - v_p), C_d' = C_d e^-4.7;
    beta = F_d (1 - e) / (V_p |u - v_p|)."""
    re = re_p(eps, rho, slip, d, mu)
    fd = pi / 8 * d ** 2 * cd_sn(re) * eps ** mpf("-4.7") * rho * (eps * slip) ** 2
    return fd * (1 - eps) / (vp(d) * slip)


def ergun_wen_yu(eps, **kw):
    """[Hoomans96 eq. 45-46]: Ergun for eps < 0.80, Wen-Yu for eps >= 0.80."""
    return ergun(eps, **kw) if eps < mpf(0.8) else wen_yu(eps, **kw)


def ergun_wen_yu_min(eps, **kw):
    """[Deen07 §3.1] the least of Ergun and Wen-Yu."""
    return min(ergun(eps, **kw), wen_yu(eps, **kw))


def hill_koch_ladd(eps, d, mu, rho, slip, **_):
    """[Deen07 eq. 5] beta d^2/mu = A es^2/e + B es Re, with A's garbled 1/es restored:
    A = 180 (e < 0.6), 18 e^3/es * (1 + 3/sqrt2 es^.5 + 135/64 es ln es + 16.14 es)
                                 / (1 + 0.681 es - 8.48 es^2 + 8.16 es^3)   (e >= 0.6),
    B = 0.6057 e^2 + 1.908 es e^2 + 0.209 e^-3."""
    es = 1 - eps
    re = re_p(eps, rho, slip, d, mu)
    if eps < mpf(0.6):
        a = mpf(180)
    else:
        a = 18 * eps ** 3 / es * (1 + 3 / sqrt(2) * sqrt(es) + mpf(135) / 64 * es * log(es)
                                  + mpf("16.14") * es) / (
            1 + mpf("0.681") * es - mpf("8.48") * es ** 2 + mpf("8.16") * es ** 3)
    b = mpf("0.6057") * eps ** 2 + mpf("1.908") * es * eps ** 2 + mpf("0.209") * eps ** -3
    return mu / d ** 2 * (a * es ** 2 / eps + b * es * re)


def beetstra_F(phi, re):
    """Beetstra, van der Hoef, Kuipers (2007), F(phi, Re) on the superficial Re."""
    e = 1 - phi
    return (10 * phi / e ** 2 + e ** 2 * (1 + mpf("1.5") * sqrt(phi))
            + mpf("0.413") * re / (24 * e ** 2)
            * (1 / e + 3 * phi * e + mpf("8.4") * re ** mpf("-0.343"))
            / (1 + mpf(10) ** (3 * phi) * re ** (-(1 + 4 * phi) / 2)))


def beetstra(eps, d, mu, rho, slip, **_):
    """beta = 18 mu e (1-e) F / d^2 (van der Hoef et al. 2005 normalisation, MFiX BVK)."""
    re = re_p(eps, rho, slip, d, mu)
    return 18 * mu * eps * (1 - eps) * beetstra_F(1 - eps, re) / d ** 2


def beetstra_poly(eps, d, mu, rho, slip, d_mean, **_):
    """Species of diameter d in a mixture of Sauter mean <d>: y = d/<d>,
    F_i = F(phi, Re_<d>) (e y + phi y^2 + 0.064 e y^3), force on one particle
    3 pi mu d e |u-v| F_i, beta_i = F_i-force (1 - e) / (V_p |u-v|)."""
    phi = 1 - eps
    y = d / d_mean
    re_mean = re_p(eps, rho, slip, d_mean, mu)
    fi = beetstra_F(phi, re_mean) * (eps * y + phi * y ** 2 + mpf("0.064") * eps * y ** 3)
    force = 3 * pi * mu * d * eps * slip * fi
    return force * (1 - eps) / (vp(d) * slip)


def di_felice(eps, d, mu, rho, slip, **_):
    """[Zhu07 Table 3; Di Felice 1994] F_d = C_d rho pi d^2/8 (e|u-v|)^2 e^-chi,
    chi = 3.7 - 0.65 exp(-(1.5 - log10 Re_p)^2/2), C_d Schiller-Naumann;
    beta = F_d (1 - e)/(V_p |u - v|)."""
    re = re_p(eps, rho, slip, d, mu)
    chi = mpf("3.7") - mpf("0.65") * exp(-(mpf("1.5") - log10(re)) ** 2 / 2)
    fd = cd_sn(re) * rho * pi * d ** 2 / 8 * (eps * slip) ** 2 * eps ** (-chi)
    return fd * (1 - eps) / (vp(d) * slip)


def koch_hill(eps, d, mu, rho, slip, **_):
    """[Zhu07 Table 3; Koch & Hill 2001] beta = 18 mu e^2 phi F / d^2, Re = e rho|u-v| d/(2 mu),
    F = F0 + F1 Re^2 (Re < 20), F0 + F3 Re (Re >= 20)."""
    phi = 1 - eps
    re = re_p(eps, rho, slip, d, mu) / 2
    if phi < mpf(0.4):
        f0 = (1 + 3 * sqrt(phi / 2) + mpf(135) / 64 * phi * log(phi) + mpf("16.14") * phi) / (
            1 + mpf("0.681") * phi - mpf("8.48") * phi ** 2 + mpf("8.16") * phi ** 3)
    else:
        f0 = 10 * phi / (1 - phi) ** 3
    f1 = mpf("0.110") + mpf("5.10e-4") * exp(mpf("11.6") * phi)
    f3 = mpf("0.0673") + mpf("0.212") * phi + mpf("0.0232") / (1 - phi) ** 5
    f = f0 + f1 * re ** 2 if re < 20 else f0 + f3 * re
    return 18 * mu * eps ** 2 * phi * f / d ** 2


THETA_S = findroot(lambda t: 150 * (1 - t) * t ** mpf("1.7") - 18, mpf("0.84"))


def chang_joint(eps, d, mu, rho, slip, **_):
    """[Chang08 §2.1] Q = beta d^2 e / ((1-e) mu) = Stokes component + deviation component, each
    from Ergun below the porosity where Ergun's and Wen-Yu's (exponent -2.7) components are equal
    and from Wen-Yu above it (thresholds as printed, in exact form):
      Re_p < 1000:  Stokes  150(1-e) if e < theta_s (= 0.8379) else 18 e^-1.7
                    inertia 1.75 Re_p if e < (2.7/1.75)^(1/2.013) Re'^(-0.313/2.013)
                            else 2.7 Re_p^0.687 e^-1.7,        Re' = rho |u-v| d / mu
      Re_p >= 1000: Stokes  150(1-e);  inertia 1.75 Re_p if e < (0.33/1.75)^(1/1.7)
                            else 0.33 Re_p e^-1.7."""
    re = re_p(eps, rho, slip, d, mu)
    re_int = rho * slip * d / mu
    if re < 1000:
        stokes = 150 * (1 - eps) if eps < THETA_S else 18 * eps ** mpf("-1.7")
        theta_i = (mpf("2.7") / mpf("1.75")) ** (1 / mpf("2.013")) * re_int ** (
            -mpf("0.313") / mpf("2.013"))
        inertia = mpf("1.75") * re if eps < theta_i else mpf("2.7") * re ** mpf("0.687") * eps ** mpf("-1.7")
    else:
        stokes = 150 * (1 - eps)
        theta_n = (mpf("0.33") / mpf("1.75")) ** (1 / mpf("1.7"))
        inertia = mpf("1.75") * re if eps < theta_n else mpf("0.33") * re * eps ** mpf("-1.7")
    q = stokes + inertia
    return q * (1 - eps) * mu / (d ** 2 * eps)


def cd_dallavalle(re):
    """Dalla Valle (1948): C_d = (0.63 + 4.8/sqrt(Re))^2 [MFiX C_DSXRE_DV; Di Felice 1994]."""
    return (mpf("0.63") + mpf("4.8") / sqrt(re)) ** 2


def syamlal_obrien(eps, d, mu, rho, slip, **_):
    """Syamlal & O'Brien as in MFiX (DRAG_SYAM_OBRIEN, default c1 = 0.8, d1 = 2.65):
    Re = rho |u-v| d / mu (interstitial, no eps), A = e^4.14, B = 0.8 e^1.28 (e <= 0.85) else
    e^2.65, V_r = (A - 0.06 Re + sqrt((0.06 Re)^2 + 0.12 Re (2B - A) + A^2))/2,
    C_d = (0.63 + 4.8 sqrt(V_r/Re))^2, beta = 3/4 (1-e) e rho C_d |u-v| / (V_r^2 d)."""
    re = rho * slip * d / mu
    a = eps ** mpf("4.14")
    b = mpf("0.8") * eps ** mpf("1.28") if eps <= mpf(0.85) else eps ** mpf("2.65")
    vr = (a - mpf("0.06") * re + sqrt((mpf("0.06") * re) ** 2 + mpf("0.12") * re * (2 * b - a)
                                      + a ** 2)) / 2
    cd = (mpf("0.63") + mpf("4.8") * sqrt(vr / re)) ** 2
    return mpf(3) / 4 * (1 - eps) * eps * rho * cd * slip / (vr ** 2 * d)


def tenneti_garg_subramaniam(eps, d, mu, rho, slip, **_):
    """Tenneti, Garg & Subramaniam (2011): F_T = F_isol(Re_m)/(1-phi)^3 + F_phi + F_phi,Re,
    F_isol = 1 + 0.15 Re_m^0.687, F_phi = 5.81 phi/(1-phi)^3 + 0.48 phi^(1/3)/(1-phi)^4,
    F_phi,Re = phi^3 Re_m (0.95 + 0.61 phi^3/(1-phi)^2), Re_m = (1-phi) rho |u-v| d / mu.
    F_T = total fluid-particle force (mean pressure gradient included) / (3 pi mu d (1-phi)|u-v|);
    the drag without the pressure-gradient part is (1 - phi) times the total (-grad p = n F_total,
    V_p n = phi); beta = drag (1 - e) / (V_p |u-v|)."""
    phi = 1 - eps
    re_m = re_p(eps, rho, slip, d, mu)
    f_isol = 1 + mpf("0.15") * re_m ** mpf("0.687")
    f_phi = mpf("5.81") * phi / (1 - phi) ** 3 + mpf("0.48") * phi ** (mpf(1) / 3) / (1 - phi) ** 4
    f_phi_re = phi ** 3 * re_m * (mpf("0.95") + mpf("0.61") * phi ** 3 / (1 - phi) ** 2)
    f_t = f_isol / (1 - phi) ** 3 + f_phi + f_phi_re
    total = 3 * pi * mu * d * (1 - phi) * slip * f_t
    drag = (1 - phi) * total
    return drag * (1 - eps) / (vp(d) * slip)


def rong_2013(eps, d, mu, rho, slip, **_):
    """Rong, Dong & Yu (2013): F_d = C_d rho pi d^2/8 (e |u-v|)^2 e^-beta_R,
    beta_R = 2.65 (e + 1) - (5.3 - 3.5 e) e^2 exp(-(1.5 - log10 Re_p)^2/2), C_d Dalla Valle on
    Re_p = e rho |u-v| d/mu; beta = F_d (1 - e)/(V_p |u-v|)."""
    re = re_p(eps, rho, slip, d, mu)
    beta_r = mpf("2.65") * (eps + 1) - (mpf("5.3") - mpf("3.5") * eps) * eps ** 2 * exp(
        -(mpf("1.5") - log10(re)) ** 2 / 2)
    fd = cd_dallavalle(re) * rho * pi * d ** 2 / 8 * (eps * slip) ** 2 * eps ** (-beta_r)
    return fd * (1 - eps) / (vp(d) * slip)


def tang_2015(eps, d, mu, rho, slip, **_):
    """Tang, Peters, Kuipers, Kriebitzsch, van der Hoef (2015) [eq. 21 as cited by MFiX TPKKV]:
    F = 10 phi/(1-phi)^2 + (1-phi)^2 (1 + 1.5 sqrt(phi)) + [0.11 phi (1+phi) - 0.00456/(1-phi)^4
        + (0.169 (1-phi) + 0.0644/(1-phi)^4) Re^-0.343] Re,  Re = (1-phi) rho |u-v| d/mu;
    beta = 18 mu (1-phi) phi F / d^2 (Beetstra's normalisation, MFiX)."""
    phi = 1 - eps
    re = re_p(eps, rho, slip, d, mu)
    f = (10 * phi / (1 - phi) ** 2 + (1 - phi) ** 2 * (1 + mpf("1.5") * sqrt(phi))
         + (mpf("0.11") * phi * (1 + phi) - mpf("0.00456") / (1 - phi) ** 4
            + (mpf("0.169") * (1 - phi) + mpf("0.0644") / (1 - phi) ** 4) * re ** mpf("-0.343"))
         * re)
    return 18 * mu * (1 - phi) * phi * f / d ** 2


CLOSURES = {
    "ergun": (ergun, "Ergun 1952 [Hoomans96 eq. 45; Deen07 eq. 3]"),
    "wen_yu": (wen_yu, "Wen & Yu 1966 [Hoomans96 eq. 46-47; Deen07 eq. 4]"),
    "wen_yu_single": (wen_yu_single, "single-particle Wen-Yu [Hoomans96 eq. 35-39]"),
    "ergun_wen_yu": (ergun_wen_yu, "Ergun/Wen-Yu switch at eps = 0.8 [Hoomans96 eq. 45-46]"),
    "ergun_wen_yu_min": (ergun_wen_yu_min, "min(Ergun, Wen-Yu) [Deen07 §3.1]"),
    "hill_koch_ladd": (hill_koch_ladd, "Hill-Koch-Ladd 2001 [Deen07 eq. 5, A reconstructed]"),
    "beetstra": (beetstra, "Beetstra-van der Hoef-Kuipers 2007 [Deen07 eq. 6]"),
    "beetstra_poly": (beetstra_poly, "Beetstra 2007 polydisperse [Deen07 eq. 6, §5]"),
    "di_felice": (di_felice, "Di Felice 1994 voidage function [Zhu07 Table 3]"),
    "koch_hill": (koch_hill, "Koch & Hill 2001 [Zhu07 Table 3]"),
    "chang_joint": (chang_joint, "joint Ergun/Wen-Yu correlation [Chang08 §2.1]"),
    "syamlal_obrien": (syamlal_obrien,
                       "Syamlal & O'Brien as in MFiX DRAG_SYAM_OBRIEN (c1 = 0.8, d1 = 2.65)"),
    "tenneti_garg_subramaniam": (tenneti_garg_subramaniam,
                                 "Tenneti, Garg & Subramaniam 2011, IJMF 37, 1072"),
    "rong_2013": (rong_2013, "Rong, Dong & Yu 2013, CES 99, 44 (Dalla Valle C_d)"),
    "tang_2015": (tang_2015, "Tang et al. 2015, AIChE J. 61, 688, eq. 21 (as cited by MFiX)"),
}

# Air-like gas, 1 mm particles; (eps, target Re_p). Spans eps 0.4-1.0, Re_p 0.1-2000, the
# eps = 0.6 (HKL) and 0.8 (switch) boundaries from both sides, Re_p = 1000 from both sides,
# Re_p = 40 (Koch-Hill radius Re = 20) from both sides, and the single particle.
MU = 1.8e-5
RHO = 1.2
D = 1.0e-3
POINTS = [
    (0.40, 0.1), (0.45, 20.0), (0.55, 39.0), (0.60, 41.0), (0.70, 300.0), (0.79, 100.0),
    (0.80, 100.0), (0.85, 999.0), (0.90, 1001.0), (0.95, 5.0), (0.99, 2000.0),
    (1.0, 0.1), (1.0, 30.0), (1.0, 1500.0),
]
# Polydisperse: (eps, Re on <d>, d/<d>)
POLY_POINTS = [
    (0.40, 0.1, 0.6), (0.50, 20.0, 1.5), (0.65, 300.0, 1.0), (0.80, 999.0, 0.8),
    (0.90, 1001.0, 1.25), (1.0, 0.1, 1.0), (1.0, 50.0, 2.0),
]


def fmt(x):
    return repr(float(x))


def case_inputs(eps, re_target, y=None):
    eps_f = float(eps)
    if y is None:
        d = D
        slip = re_target * MU / (eps_f * RHO * d)
        return dict(eps=eps_f, d=d, mu=MU, rho=RHO, slip=slip)
    d_mean = D
    d = y * d_mean
    slip = re_target * MU / (eps_f * RHO * d_mean)
    return dict(eps=eps_f, d=d, mu=MU, rho=RHO, slip=slip, d_mean=d_mean)


def evaluate(fn, inputs):
    """beta at the given eps; F from beta, or at eps = 1 - 1e-30 for the single particle."""
    m = {k: mpf(v) for k, v in inputs.items()}  # exact binary values of the doubles
    eps = m.pop("eps")
    e_eval = 1 - TINY if eps == 1 else eps
    beta_eval = fn(e_eval, **m)
    f = beta_eval * m["d"] ** 2 / (18 * m["mu"] * e_eval * (1 - e_eval))
    beta = mpf(0) if eps == 1 else beta_eval
    return beta, f, re_p(eps, m["rho"], m["slip"], m.get("d_mean", m["d"]), m["mu"])


def write(name):
    fn, source = CLOSURES[name]
    poly = name == "beetstra_poly"
    pts = POLY_POINTS if poly else POINTS
    lines = [
        f"# Drag closure '{name}': {source}.",
        "# Generated by tools/drag_reference.py (mpmath, 50 digits, the published formulas; not the",
        "# C++). Do not edit by hand: change the script and re-run it.",
        "#   beta : kg m^-3 s^-1, force per unit mixture volume = beta (u - v)",
        "#   F    : drag on one particle / (3 pi mu d eps |u - v|)",
        "#   re_p : eps rho |u - v| d / mu (on d_mean for beetstra_poly), for information",
        "# eps = 1: beta = 0 exactly; F is the single-particle limit (evaluated at eps = 1 - 1e-30).",
        f'closure = "{name}"',
        "tolerance = 1e-9  # relative (absolute 1e-300 for beta = 0)",
        "",
    ]
    for p in pts:
        if poly:
            eps, re_t, y = p
            inputs = case_inputs(eps, re_t, y)
            label = f"eps{eps}_re{re_t}_y{y}"
        else:
            eps, re_t = p
            inputs = case_inputs(eps, re_t)
            label = f"eps{eps}_re{re_t}"
        beta, f, re = evaluate(fn, inputs)
        lines.append("[[case]]")
        lines.append(f'name = "{label}"')
        for k in ("eps", "d", "mu", "rho", "slip", "d_mean"):
            if k in inputs:
                lines.append(f"{k} = {fmt(inputs[k])}")
        lines.append(f"re_p = {mp.nstr(re, 17)}")
        lines.append("[case.expected]")
        lines.append(f"beta = {mp.nstr(beta, 17) if beta != 0 else '0.0'}")
        lines.append(f"F = {mp.nstr(f, 17)}")
        lines.append("")
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, f"{name}.toml"), "w") as fh:
        fh.write("\n".join(lines))


if __name__ == "__main__":
    for n in CLOSURES:
        write(n)
    print(f"wrote {len(CLOSURES)} files to {os.path.normpath(OUT)}")
