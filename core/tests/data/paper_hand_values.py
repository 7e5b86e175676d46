# Hand values for core/tests/library/paper_hand_values.rs from the papers equations (Polach eqs. 20-25 with
# ERRATA E2-E4, E7; Shen-Hedrick-Elkins cubic), independent of the crate. Run: python3 core/tests/data/paper_hand_values.py
from math import *
# Contact: a = 8 mm, b = 4 mm (a/b = 2: table row b/a = 0.5), Q = 82 kN, mu = 0.3, G = 82 GPa, nu = 0.25
a, b, Q, f, G = 8e-3, 4e-3, 82e3, 0.3, 82e9
C11, C22, C23 = 5.10, 4.90, 2.62   # Table E.3, row b/a = 0.5, nu = 0.25
KS = 1 + 6.3*(1 - exp(-a/b))
print("K_S(a/b=2) =", repr(KS), " K_S(0.5) =", repr(1 + 6.3*(1-exp(-0.5))))
def KM(e):  # eq. (20) as printed, with delta of eq. (12)
    d = (e*e-1)/(e*e+1)
    return abs(e)*(d**3/3 - d*d/2 + 1/6) - sqrt((1-d*d)**3)/3
# Pure spin Phi: s_yC = a*Phi, s_C = |a Phi|, F_y = (9/16) a Q f K_M K_S Phi / s_C  (E4)
for Phi in [0.05, 0.2, 1.0]:
    syc = a*Phi
    eps_s = 8/3*G*b*sqrt(a*b)*C23*abs(syc)/(Q*f*KS)   # E2
    Fy = 9/16*a*Q*f*KM(eps_s)*KS*Phi/abs(syc)
    print(f"pure spin Phi={Phi}: eps_s={eps_s!r} K_M={KM(eps_s)!r} F_y={Fy!r}  linear -G(ab)^1.5 C23 Phi = {-G*(a*b)**1.5*C23*Phi!r}")
# Combined eta = 1e-3, Phi = 0.2 (a Phi = 1.6e-3, same sign): s_yC = 2.6e-3, xi = 0
eta, Phi = 1e-3, 0.2
syc = eta + a*Phi; sc = syc
eps = pi*G*a*b*C22*sc/(4*Q*f)       # E3 with c_jj = C22 (pure lateral)
F = 2*Q*f/pi*(eps/(1+eps*eps) + atan(eps))
eps_s = 8/3*G*b*sqrt(a*b)*C23*abs(syc)/(Q*f*KS)
Fy = -F*eta/sc + 9/16*a*Q*f*KM(eps_s)*KS*Phi/sc
print(f"combined: eps={eps!r} F={F!r} eps_s={eps_s!r} F_y={Fy!r}")
# Measured curve: F_max/Q = 0.36, s_max = 3e-3, f_k = 0.3, Coulomb mu = f_k
fmax, smax, fk = 0.36, 3e-3, 0.3
def shape(k, e): return 2/pi*(k*e/(k*k+e*e) + atan(e))
def peak(k):
    lo, hi = 1e-6, 1e6
    for _ in range(300):  # golden search on log scale for the maximum
        m1 = exp(log(lo) + (log(hi)-log(lo))*0.382); m2 = exp(log(lo) + (log(hi)-log(lo))*0.618)
        if shape(k, m1) < shape(k, m2): lo = m1
        else: hi = m2
    e = sqrt(lo*hi); return e, shape(k, e)
lo, hi = 1.0 + 1e-12, 1e6
for _ in range(200):
    k = sqrt(lo*hi)
    if peak(k)[1] < fmax/fk: lo = k
    else: hi = k
k = sqrt(lo*hi); emax, pk = peak(k)
print("measured: k =", repr(k), "eps_max =", repr(emax), "peak/fk", pk)
# eq. (25) with the measured curve's C: kappa_s = kappa / K_S, kappa = eps_max/s_max at f = f_k
Phi = smax/2/a   # a Phi = s_max/2
syc = a*Phi
eps_s = emax*abs(syc)/smax/KS
Fy = 9/16*a*Q*f*KM(eps_s)*KS*Phi/abs(syc)
print(f"measured pure spin Phi={Phi!r}: eps_s={eps_s!r} F_y={Fy!r}; without 1/K_S F_y would be {9/16*a*Q*f*KM(emax*abs(syc)/smax)*KS*Phi/abs(syc)!r}")
# Also check measured curve main force at s = s_max (pure xi): F = f_k Q shape(k, eps_max) = F_max
# SHE: beta = F'/(mu Q); F = mu Q (beta - beta^2/3 + beta^3/27)
muQ = f*Q
for beta in [0.3, 1.5, 2.0, 2.9]:
    print(f"SHE beta={beta}: xi={beta*muQ/(G*a*b*C11)!r} F_x={-muQ*(beta-beta**2/3+beta**3/27)!r}")
# combined SHE: xi and eta with F'x = 1.2 muQ, F'y = 1.6 muQ -> beta = 2
xi = 1.2*muQ/(G*a*b*C11); eta = 1.6*muQ/(G*a*b*C22)
fac = (2 - 4/3 + 8/27)/2
print(f"SHE combined: xi={xi!r} eta={eta!r} F_x={-1.2*muQ*fac!r} F_y={-1.6*muQ*fac!r}")
