#!/usr/bin/python3
"""Independent Lagrangian derivation of the gimbal-gyro equations of motion, and the oracle vectors for
tests/oracle/gimbal_gyro_equations_test.cpp.

Run:  /usr/bin/python3 tools/derive/gimbal_gyro_lagrange.py          (from the repository root)
      (python3 + sympy + mpmath; Debian's python3-sympy)
It regenerates tests/oracle/data/gimbal_gyro_lagrange_vectors.inc deterministically: the random draws come
from random.Random(SEED) with a fixed SEED, the reference accelerations are evaluated in 50-digit mpmath
arithmetic on the exact binary values of the doubles written to the file, then rounded once to double and
printed with 17 significant digits (so the file is byte-identical on every run and round-trips exactly).
Pass --check-only to run the symbolic derivation and book checks without writing the file.

What is derived (models/gimbal_gyro.hpp uses Kane's method; this script deliberately does not):
  Bodies (book §4.2, (4.31)): outer gimbal A, diag(A^A, B^A, C^A), turned by α about base axis 1;
  inner gimbal J, diag(A^J, B^J, C^J), turned by β about A's axis 2; symmetric rotor R, diag(A^R, A^R, C^R),
  turned by γ about J's axis 3 (Cardan sequence x-y-z, (1.47)). The base B has a prescribed absolute angular
  velocity Ω(t) in base axes (sympy Functions of t, so dΩ/dt appears by differentiation). The Lagrangian is
  built from the *absolute* angular velocities, so Lagrange's equations hold for this rheonomic system.
  Potential V = Gs (e3_J · up_B), up_B = (u1, u2, u3) the specific force / g in base axes; for the EOM at one
  instant up_B may be treated as given (it enters V explicitly in t and only -∂V/∂q is needed).
  Generalised forces from the virtual power of every torque pair acting across a joint:
    outer bearing  (M1 - d1 α' - r1 sgnreg(α')) on A, its reaction on the base   -> Q_α
    inner bearing  (M2 - d2 β' - r2 sgnreg(β')) on J, its reaction on A          -> Q_β
    rotor motor     M3 on R, its reaction -M3 on J                                -> Q_γ only
  (The motor pair's power is M3 e3·(ω_R - ω_J) = M3 γ': its generalised force on α and β is exactly zero.)

Routh reduction with a time-varying spin momentum:
  γ is cyclic (∂L/∂γ = 0, checked below), p_γ = ∂L/∂γ' = C^R(ω_J3 + γ') =: H, and its Lagrange equation is
  dH/dt = Q_γ = M3. With γ' eliminated through p_γ = H, R(q, q', H, t) = L - H γ'. The identities
  ∂R/∂q'|_H = ∂L/∂q'|_γ' and ∂R/∂q|_H = ∂L/∂q|_γ' are pointwise (they hold for whatever value H has at that
  instant), so d/dt ∂R/∂q' - ∂R/∂q = Q_q holds for time-varying H too, PROVIDED the total time derivative also
  differentiates H(t): R contains H ω_J3(q, q', t), so d/dt ∂R/∂α' carries Ḣ ∂ω_J3/∂α' = M3 sinβ. That term is
  how the motor reaction reaches the gimbals; adding a separate "-M3 sinβ" generalised force would count it
  twice. Both points are verified below by deriving the full 3-DOF Lagrange equations (γ kept) and
  eliminating γ'' and γ', which must give the same α'', β''.

Book checks (Magnus, docs/models/gimbal-gyro.md): kinematics (1.47), (1.51), (4.32); the
kinetic energy (4.34); (10.4)-(10.7) for a fixed base with up = (cos δ, 0, sin δ); (4.45) (δ = 0, M = 0);
the small-angle rotating-frame equations (10.22) as the first-order part in ε of the full equations with
α, β, α', β', Ω, Ω' = O(ε).
"""

import argparse
import pathlib
import random
import sys

import mpmath
import sympy as sp

SEED = 20250611
N_VECTORS = 20
OUT = pathlib.Path(__file__).resolve().parents[2] / "tests/oracle/data/gimbal_gyro_lagrange_vectors.inc"

t = sp.Symbol("t", real=True)
al_f, be_f, ga_f = (sp.Function(n)(t) for n in ("alpha", "beta", "gamma"))
Om_f = sp.Matrix([sp.Function(f"Omega{i}")(t) for i in (1, 2, 3)])
H_f = sp.Function("H")(t)

AR, CR, AJ, BJ, CJ, AA, BA, CA = sp.symbols("A_R C_R A_J B_J C_J A_A B_A C_A", real=True)
Gs, d1, d2, r1, r2, vc, M1, M2, M3 = sp.symbols("G_s d_1 d_2 r_1 r_2 v_c M_1 M_2 M_3", real=True)
u = sp.Matrix(sp.symbols("u1 u2 u3", real=True))

# Plain symbols that replace the functions of t once the differentiations are done.
a, b, g = sp.symbols("alpha beta gamma", real=True)
ad, bd, gd = sp.symbols("alphad betad gammad", real=True)
add, bdd, gdd = sp.symbols("alphadd betadd gammadd", real=True)
W = sp.Matrix(sp.symbols("W1 W2 W3", real=True))
dW = sp.Matrix(sp.symbols("dW1 dW2 dW3", real=True))
H, Hd = sp.symbols("H Hd", real=True)


def to_symbols(expr):
    """Replace α(t), α'(t), α''(t), ..., Ω(t), Ω'(t), H(t), H'(t) by plain symbols (highest derivative
    first)."""
    rep = {}
    for f, s0, s1, s2 in ((al_f, a, ad, add), (be_f, b, bd, bdd), (ga_f, g, gd, gdd)):
        rep[f.diff(t, 2)] = s2
        rep[f.diff(t)] = s1
    for i in range(3):
        rep[Om_f[i].diff(t)] = dW[i]
    rep[H_f.diff(t)] = Hd
    expr = expr.subs(rep)
    rep2 = {al_f: a, be_f: b, ga_f: g, H_f: H}
    rep2.update({Om_f[i]: W[i] for i in range(3)})
    return expr.subs(rep2)


def Rx(q):
    c, s = sp.cos(q), sp.sin(q)
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


def Ry(q):
    c, s = sp.cos(q), sp.sin(q)
    return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def Rz(q):
    c, s = sp.cos(q), sp.sin(q)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def sgnreg(v):
    return v / sp.sqrt(v**2 + vc**2)


def is_zero(expr):
    e = sp.expand(sp.expand_trig(expr))
    if e == 0:
        return True
    return sp.simplify(sp.trigsimp(e)) == 0


def check(name, ok):
    print(f"  [{'ok' if ok else 'FAIL'}] {name}")
    if not ok:
        raise SystemExit(f"check failed: {name}")


# ---------------------------------------------------------------------------------------------------------
# Kinematics. R_XY rotates Y-axis components into X-axis components.
R_BA, R_AJ, R_JR = Rx(al_f), Ry(be_f), Rz(ga_f)
w_A_A = R_BA.T * Om_f + sp.Matrix([al_f.diff(t), 0, 0])  # absolute ω of A, in A axes
w_J_J = R_AJ.T * w_A_A + sp.Matrix([0, be_f.diff(t), 0])  # absolute ω of J, in J axes
w_R_R = R_JR.T * w_J_J + sp.Matrix([0, 0, ga_f.diff(t)])  # absolute ω of R, in R axes

I_A = sp.diag(AA, BA, CA)
I_J = sp.diag(AJ, BJ, CJ)
I_R = sp.diag(AR, AR, CR)
T = (w_A_A.T * I_A * w_A_A)[0] / 2 + (w_J_J.T * I_J * w_J_J)[0] / 2 + (w_R_R.T * I_R * w_R_R)[0] / 2
e3_J_B = R_BA * R_AJ * sp.Matrix([0, 0, 1])
V = Gs * e3_J_B.dot(u)
L = T - V

# Virtual power of the joint torques; each torque is a given value at the instant (placeholders τ1, τ2).
tau1, tau2 = sp.symbols("tau1 tau2", real=True)
rel_A = w_A_A - R_BA.T * Om_f  # A relative to the base, A axes
rel_J = w_J_J - R_AJ.T * w_A_A  # J relative to A, J axes
rel_R = w_R_R - R_JR.T * w_J_J  # R relative to J, R axes (e3_R = e3_J)
power = tau1 * rel_A[0] + tau2 * rel_J[1] + M3 * rel_R[2]
tau_values = {tau1: M1 - d1 * ad - r1 * sgnreg(ad), tau2: M2 - d2 * bd - r2 * sgnreg(bd)}


def gen_force(qdot_f):
    return to_symbols(power.diff(qdot_f)).subs(tau_values)


Q_al, Q_be, Q_ga = gen_force(al_f.diff(t)), gen_force(be_f.diff(t)), gen_force(ga_f.diff(t))


def run_checks_kinematics():
    print("Kinematics and forces:")
    R = to_symbols(R_BA * R_AJ * R_JR)
    book_147 = sp.Matrix([
        [sp.cos(b) * sp.cos(g), -sp.cos(b) * sp.sin(g), sp.sin(b)],
        [sp.cos(a) * sp.sin(g) + sp.sin(a) * sp.sin(b) * sp.cos(g),
         sp.cos(a) * sp.cos(g) - sp.sin(a) * sp.sin(b) * sp.sin(g), -sp.sin(a) * sp.cos(b)],
        [sp.sin(a) * sp.sin(g) - sp.cos(a) * sp.sin(b) * sp.cos(g),
         sp.sin(a) * sp.cos(g) + sp.cos(a) * sp.sin(b) * sp.sin(g), sp.cos(a) * sp.cos(b)]])
    check("R_BA R_AJ R_JR is the Cardan matrix (1.47)", all(is_zero(x) for x in (R - book_147)))
    fixed = {W[i]: 0 for i in range(3)}
    wR = to_symbols(w_R_R).subs(fixed)
    book_151 = sp.Matrix([ad * sp.cos(b) * sp.cos(g) + bd * sp.sin(g),
                          -ad * sp.cos(b) * sp.sin(g) + bd * sp.cos(g), gd + ad * sp.sin(b)])
    check("rotor ω on a fixed base is (1.51)", all(is_zero(x) for x in (wR - book_151)))
    wJ = to_symbols(w_J_J).subs(fixed)
    check("inner-gimbal ω on a fixed base is (4.32)",
          all(is_zero(x) for x in (wJ - sp.Matrix([ad * sp.cos(b), bd, ad * sp.sin(b)]))))
    check("rotor axis in base axes is the third column of (1.47)",
          all(is_zero(x) for x in (to_symbols(e3_J_B) - book_147[:, 2])))
    Ts = to_symbols(T).subs(fixed)
    A_, B_, P_ = AA + AJ + AR, BJ + AR, AA + CJ
    book_434 = (ad**2 * (A_ * sp.cos(b)**2 + P_ * sp.sin(b)**2) + B_ * bd**2
                + CR * (gd + ad * sp.sin(b))**2) / 2
    check("kinetic energy on a fixed base is (4.34)", is_zero(Ts - book_434))
    check("γ is cyclic: ∂L/∂γ = 0 (symmetric rotor), with base rotation",
          is_zero(to_symbols(L.diff(ga_f))))
    check("motor torque pair: generalised force on α and β is 0, on γ is M3",
          is_zero(Q_al - tau_values[tau1]) and is_zero(Q_be - tau_values[tau2]) and is_zero(Q_ga - M3))


# ---------------------------------------------------------------------------------------------------------
# Route 1 (primary): Routh reduction of γ with the spin momentum H(t) a given function of time.
def routh_equations():
    gdot = sp.Symbol("gdot_tmp")
    # γ' becomes a plain symbol first; then γ = 0, which changes nothing: L does not depend on γ (checked).
    Lg = L.subs(ga_f.diff(t), gdot).subs(ga_f, 0)
    p_g = sp.diff(Lg, gdot)
    gdot_of_H = sp.solve(sp.Eq(p_g, H_f), gdot)
    assert len(gdot_of_H) == 1
    R = (Lg - H_f * gdot).subs(gdot, gdot_of_H[0])
    eqs = []
    for q_f, Qq in ((al_f, Q_al), (be_f, Q_be)):
        lhs = sp.diff(R, q_f.diff(t)).diff(t) - sp.diff(R, q_f)
        eqs.append(sp.expand(to_symbols(lhs).subs(Hd, M3)) - Qq)  # Ḣ = Q_γ = M3 (the γ equation)
    p_g_sym = sp.expand(to_symbols(p_g).subs(gdot, gd))
    return eqs, p_g_sym


# Route 2 (cross-check of the reduction): the full 3-DOF Lagrange equations, then γ'' and γ' eliminated.
def full_equations(p_g_sym):
    eqs = []
    for q_f, Qq in ((al_f, Q_al), (be_f, Q_be), (ga_f, Q_ga)):
        lhs = sp.diff(L, q_f.diff(t)).diff(t) - sp.diff(L, q_f)
        eqs.append(to_symbols(lhs) - Qq)
    # γ equation is d/dt p_γ = M3; it is linear in γ''. Solve it for γ'' and use p_γ = H for γ'.
    gdd_sol = sp.solve(eqs[2], gdd)
    assert len(gdd_sol) == 1
    gd_sol = sp.solve(sp.Eq(p_g_sym, H), gd)
    assert len(gd_sol) == 1
    out = []
    for e in eqs[:2]:
        e = e.subs(gdd, gdd_sol[0]).subs(gd, gd_sol[0])
        out.append(e)
    return out


def solve_accelerations(eqs):
    Mm = sp.Matrix([[sp.diff(e, x) for x in (add, bdd)] for e in eqs])
    rest = [sp.expand(e.subs({add: 0, bdd: 0})) for e in eqs]  # E = M q'' + rest
    return Mm, rest


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--check-only", action="store_true")
    args = ap.parse_args()

    run_checks_kinematics()

    print("Routh reduction:")
    eqs, p_g_sym = routh_equations()
    check("p_γ = C^R (ω_J3 + γ')",
          is_zero(p_g_sym - CR * (to_symbols(w_J_J[2]) + gd)))
    Mm, rest = solve_accelerations(eqs)
    A_, B_, P_, Q_ = AA + AJ + AR, BJ + AR, AA + CJ, AR + AJ - CJ
    check("mass matrix is diag(A cos²β + P sin²β, B) (no α''-β'' coupling, even with base rotation)",
          is_zero(Mm[0, 0] - (A_ * sp.cos(b)**2 + P_ * sp.sin(b)**2)) and Mm[0, 1] == 0 and Mm[1, 0] == 0
          and is_zero(Mm[1, 1] - B_))
    acc_al = -rest[0] / Mm[0, 0]
    acc_be = -rest[1] / Mm[1, 1]

    print("Full 3-DOF Lagrange equations, γ'' and γ' eliminated afterwards:")
    full = full_equations(p_g_sym)
    check("α equation identical to the Routh form (so Routh holds with Ḣ = M3 ≠ 0)",
          is_zero(sp.expand(full[0]) - eqs[0]))
    check("β equation identical to the Routh form", is_zero(sp.expand(full[1]) - eqs[1]))
    # So the motor reaction enters the reduced equations only as Ḣ ∂ω_J3/∂α' = M3 sinβ in the α row: treating
    # H as constant inside d/dt would lose it, adding it as a generalised force as well would double it.
    check("M3 enters the α row as +M3 sinβ (from Ḣ) and not the β row",
          is_zero(sp.diff(eqs[0], M3) - sp.sin(b)) and sp.diff(eqs[1], M3) == 0)

    print("Book special cases:")
    delta = sp.Symbol("delta", real=True)
    fixed = {W[0]: 0, W[1]: 0, W[2]: 0, dW[0]: 0, dW[1]: 0, dW[2]: 0,
             u[0]: sp.cos(delta), u[1]: 0, u[2]: sp.sin(delta), d1: 0, d2: 0, r1: 0, r2: 0, M3: 0}
    E_al, E_be = (sp.expand(e.subs(fixed)) for e in eqs)
    M1g = M1 + Gs * sp.sin(delta) * sp.cos(b) * sp.sin(a)                               # (10.6)
    M2g = M2 - Gs * (sp.cos(delta) * sp.cos(b) - sp.sin(delta) * sp.sin(b) * sp.cos(a))  # (10.7)
    book_104 = ((A_ * sp.cos(b)**2 + P_ * sp.sin(b)**2) * add - Q_ * sp.sin(2 * b) * ad * bd
                + H * sp.cos(b) * bd - M1g)
    book_105 = B_ * bdd + Q_ * sp.sin(b) * sp.cos(b) * ad**2 - H * sp.cos(b) * ad - M2g
    check("(10.4) with gravity (10.6): fixed base, up = (cos δ, 0, sin δ)", is_zero(E_al - book_104))
    check("(10.5) with gravity (10.7)", is_zero(E_be - book_105))
    book_445 = B_ * bdd + Q_ * sp.sin(b) * sp.cos(b) * ad**2 - H * sp.cos(b) * ad + Gs * sp.cos(b)
    check("(4.45): outer axis vertical (δ = 0), no torques",
          is_zero(E_be.subs({delta: 0, M2: 0}) - book_445))

    # (10.22): two small parameters. The gimbal state (α, β and rates, M1, M2) is O(ε); the base rate
    # (Ω, Ω') is O(η). The book keeps O(ε) and O(η), and of the O(εη) terms only those carrying H (H Ω3 α,
    # H Ω3 β): it drops inertia·Ω·(state) and inertia·Ω·Ω (O(η²)) as small against H·(state) and H·Ω, the
    # "fast gyro" assumption |Ω|·(A, B) ≪ H of §10.2. Checked: what the book keeps is exactly reproduced, and
    # everything it drops at these orders is printed and contains no H. Gs = 0 and no friction, as in (10.22).
    eps, eta = sp.symbols("epsilon eta", positive=True)
    small = {a: eps * a, b: eps * b, ad: eps * ad, bd: eps * bd, add: eps * add, bdd: eps * bdd,
             M1: eps * M1, M2: eps * M2, Gs: 0, d1: 0, d2: 0, r1: 0, r2: 0, M3: 0}
    small.update({W[i]: eta * W[i] for i in range(3)})
    small.update({dW[i]: eta * dW[i] for i in range(3)})
    at0 = {eps: 0, eta: 0}

    def orders(e):
        es = e.xreplace(small)
        c0 = sp.expand(es.subs(at0))
        c_e = sp.expand(sp.diff(es, eps).subs(at0))
        c_h = sp.expand(sp.diff(es, eta).subs(at0))
        c_eh = sp.expand(sp.diff(es, eps, eta).subs(at0))
        c_hh = sp.expand(sp.diff(es, eta, 2).subs(at0) / 2)
        return c0, c_e, c_h, c_eh, c_hh

    book_1022 = (A_ * add + H * bd + H * W[2] * a - (M1 - A_ * dW[0] - H * W[1]),
                 B_ * bdd - H * ad + H * W[2] * b - (M2 - B_ * dW[1] + H * W[0]))
    names = ("(10.22) α row: A α'' + H β' + H Ω3 α = M1 - A Ω1' - H Ω2",
             "(10.22) β row: B β'' - H α' + H Ω3 β = M2 - B Ω2' + H Ω1")
    for e, book, name in zip(eqs, book_1022, names):
        c0, c_e, c_h, c_eh, c_hh = orders(e)
        kept_eh = sum((x for x in sp.Add.make_args(c_eh) if x.has(H)), sp.Integer(0))
        dropped = sp.expand(c_eh - kept_eh + c_hh)
        check(name, c0 == 0 and is_zero(c_e + c_h + kept_eh - book))
        check("   ... dropped O(εη), O(η²) terms carry no H: " + str(sp.factor_terms(dropped)),
              not dropped.has(H))

    if args.check_only:
        return

    # -----------------------------------------------------------------------------------------------------
    # Reference vectors. Scale per row: Σ|additive terms of the numerator| / mass, an upper bound on |acc|
    # that sets the size of double round-off in any evaluation order (the test's tolerance is relative to it).
    mpmath.mp.dps = 50
    inputs = [AR, CR, AJ, BJ, CJ, AA, BA, CA, Gs, d1, d2, r1, r2, vc, a, b, ad, bd, H, M1, M2, M3,
              *W, *dW, *u]
    f_al = sp.lambdify(inputs, acc_al, "mpmath")
    f_be = sp.lambdify(inputs, acc_be, "mpmath")
    terms_al = [sp.lambdify(inputs, x, "mpmath") for x in sp.Add.make_args(rest[0])]
    terms_be = [sp.lambdify(inputs, x, "mpmath") for x in sp.Add.make_args(rest[1])]
    m_al = sp.lambdify(inputs, Mm[0, 0], "mpmath")
    m_be = sp.lambdify(inputs, Mm[1, 1], "mpmath")

    rng = random.Random(SEED)

    def uni(lo, hi):
        return rng.uniform(lo, hi)

    def signed_log(lo, hi):
        return rng.choice((-1.0, 1.0)) * 10.0 ** rng.uniform(lo, hi)

    rows = []
    for k in range(N_VECTORS):
        AR_, CR_ = uni(0.05, 2.0), uni(0.05, 3.0)
        AJ_, BJ_, CJ_ = uni(0.0, 1.0), uni(0.0, 1.0), uni(0.0, 1.0)
        AA_, BA_, CA_ = uni(0.0, 1.5), uni(0.0, 1.5), uni(0.0, 1.5)
        if k == 0:  # massless gimbals: only the rotor (M11 = A^R cos²β)
            AJ_ = BJ_ = CJ_ = AA_ = BA_ = CA_ = 0.0
        row = dict(AR=AR_, CR=CR_, AJ=AJ_, BJ=BJ_, CJ=CJ_, AA=AA_, BA=BA_, CA=CA_,
                   Gs=uni(-5.0, 5.0),
                   d1=uni(0.0, 0.5) if k % 3 else 0.0, d2=uni(0.0, 0.5) if k % 3 else 0.0,
                   r1=uni(0.0, 0.3) if k % 4 else 0.0, r2=uni(0.0, 0.3) if k % 4 else 0.0,
                   vc=10.0 ** uni(-4.0, -1.0),
                   alpha=uni(-3.1, 3.1),
                   beta=uni(-1.45, 1.45) if k != 7 else 1.5607963267948966,  # 0.01 rad from gimbal lock
                   alpha_rate=signed_log(-4.0, 1.0), beta_rate=signed_log(-4.0, 1.0),
                   H=signed_log(-1.0, 3.0),
                   M1=uni(-3.0, 3.0), M2=uni(-3.0, 3.0), M3=uni(-3.0, 3.0) if k % 2 else 0.0,
                   w=[uni(-2.0, 2.0) for _ in range(3)], dw=[uni(-5.0, 5.0) for _ in range(3)],
                   up=[uni(-1.5, 1.5) for _ in range(3)])
        if k in (1, 2):  # base at rest (the book's setting) but with a tilted "up"
            row["w"], row["dw"] = [0.0] * 3, [0.0] * 3
        vals = [mpmath.mpf(x) for x in (
            row["AR"], row["CR"], row["AJ"], row["BJ"], row["CJ"], row["AA"], row["BA"], row["CA"],
            row["Gs"], row["d1"], row["d2"], row["r1"], row["r2"], row["vc"], row["alpha"], row["beta"],
            row["alpha_rate"], row["beta_rate"], row["H"], row["M1"], row["M2"], row["M3"],
            *row["w"], *row["dw"], *row["up"])]
        row["alpha_acc"] = float(f_al(*vals))
        row["beta_acc"] = float(f_be(*vals))
        row["alpha_scale"] = float(sum(abs(f(*vals)) for f in terms_al) / abs(m_al(*vals)))
        row["beta_scale"] = float(sum(abs(f(*vals)) for f in terms_be) / abs(m_be(*vals)))
        rows.append(row)

    def num(x):
        s = f"{x:.17g}"
        if not any(c in s for c in ".en"):
            s += ".0"
        return s

    def vec(v):
        return "{" + ", ".join(num(x) for x in v) + "}"

    lines = [
        "// Generated by tools/derive/gimbal_gyro_lagrange.py (Lagrangian + Routh reduction of the rotor angle,",
        "// independent of the Kane derivation in sim/models/gimbal_gyro.hpp). Do not edit by hand: rerun",
        "//   /usr/bin/python3 tools/derive/gimbal_gyro_lagrange.py",
        f"// which regenerates this file byte for byte (random.Random({SEED}), {N_VECTORS} vectors; references",
        "// evaluated in 50-digit arithmetic on the exact doubles below, rounded once, printed to 17 digits).",
        "// One vector per brace, one line per group:",
        "//   A^R, C^R, A^J, B^J, C^J, A^A, B^A, C^A [kg m²]",
        "//   Gs [N m], d1, d2 [N m s/rad], r1, r2 [N m], v_c [rad/s]",
        "//   α, β [rad], α', β' [rad/s], H [N m s]",
        "//   M1, M2, M3 [N m]",
        "//   w_B [rad/s]; dw_B [rad/s²]; up_B [-]   (base sample, base axes)",
        "//   α'', β'' [rad/s²] (Lagrangian reference); their round-off scales Σ|terms| / mass [rad/s²]",
        "{",
    ]
    for r in rows:
        groups = (("AR", "CR", "AJ", "BJ", "CJ", "AA", "BA", "CA"), ("Gs", "d1", "d2", "r1", "r2", "vc"),
                  ("alpha", "beta", "alpha_rate", "beta_rate", "H"), ("M1", "M2", "M3"))
        body = [", ".join(num(r[k]) for k in grp) for grp in groups]
        body += [vec(r["w"]), vec(r["dw"]), vec(r["up"])]
        body.append(", ".join(num(r[k]) for k in ("alpha_acc", "beta_acc", "alpha_scale", "beta_scale")))
        lines.append("    {" + body[0] + ",")
        lines += ["     " + x + "," for x in body[1:-1]]
        lines.append("     " + body[-1] + "},")
    lines.append("}")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n")
    print(f"wrote {len(rows)} vectors to {OUT}")


if __name__ == "__main__":
    sys.exit(main())
