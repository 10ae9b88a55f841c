#!/usr/bin/python3
"""beamid's forward run against peers written in NumPy and SciPy, measured side by side (make bench).

The computation is BM_SimulateFastPeer of forward_model_bench.cc: banks-aluminium at N = 16 (36 degrees of freedom,
a 72-dimensional state), a sin^2 pulse of 4 ms at 0.7 l, tip displacement, dt = 10 us, Nbar = 4096 samples (41 ms of
record: SciPy's BDF at rtol 1e-8 takes about a minute on it, and more than 15 minutes on the 4.1 s record of
BM_SimulateFast/16 at dt = 1 ms). The matrices come from `beamid system`, so all three solve the same model, and each
peer's output is compared with beamid's.

Peers (one thread each: the BLAS thread variables are set to 1 before NumPy is imported):
  numpy-modal  the modal closed form of simulation/modal_simulator.h written in NumPy/SciPy: undamped modes of the
               symmetric-definite pencil (scipy.linalg.eigh), the balanced modal state matrix, numpy.linalg.eig, and
               the exact sin^2-pulse response and free decay of every mode, vectorised over modes and samples.
  scipy-bdf    scipy.integrate.solve_ivp(method="BDF", rtol=1e-8) on the first-order system with its constant
               Jacobian (atol: 1e-8 of the natural size of each block, as beamid's CVODE default).

Timing: R rounds; each round times beamid (Google Benchmark, BM_SimulateFastPeer, its real time), then numpy-modal
(the median of repeated calls over about 0.5 s), so that the machine's load drifts through both alike; scipy-bdf (one
call, about a minute) runs once, in the middle round. The ratio of a round is peer time / beamid time in that round;
peers.json holds every round, the median times and the median ratios. Process start-up is in none of the times.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

for variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ[variable] = "1"

import numpy as np  # noqa: E402  (after the thread variables)
import scipy  # noqa: E402
import scipy.integrate  # noqa: E402
import scipy.linalg  # noqa: E402

# The experiment of BM_SimulateFastPeer (forward_model_bench.cc).
BEAM = "banks-aluminium"
ELEMENTS = 16
LENGTH_M = 0.4573  # banks-aluminium l; the force sits at 0.7 l as in the benchmark
EXPERIMENT = ["--dt", "1e-5", "--samples", "4096", "--pulse-width", "4e-3", "--force-x", repr(0.7 * LENGTH_M)]


def read_system(beamid):
    text = subprocess.run([beamid, "system", "--beam", BEAM, "--elements", str(ELEMENTS)] + EXPERIMENT,
                          check=True, capture_output=True, text=True).stdout
    s = json.loads(text)
    if abs(s["length_m"] - LENGTH_M) > 1e-12:
        raise RuntimeError(f"{BEAM}: l = {s['length_m']} m, but peers.py places the force for l = {LENGTH_M} m")
    for key in ("M", "C", "K", "load", "sensor", "w0"):
        s[key] = np.array(s[key], dtype=float)
    return s


def beamid_trace(beamid):
    text = subprocess.run([beamid, "simulate", "--beam", BEAM, "--elements", str(ELEMENTS)] + EXPERIMENT,
                          check=True, capture_output=True, text=True).stdout
    return np.loadtxt(text.splitlines()[1:], delimiter=",")[:, 1]


def phi1(z):
    """(e^z - 1)/z without cancellation (z -> 0 gives 1)."""
    z = np.asarray(z, dtype=complex)
    x, y = z.real, z.imag
    s = np.sin(0.5 * y)
    em1 = np.expm1(x) * np.cos(y) - 2 * s * s + 1j * np.exp(x) * np.sin(y)
    small = np.abs(z) < 1e-8
    out = np.empty_like(z)
    out[~small] = em1[~small] / z[~small]
    out[small] = 1 + 0.5 * z[small]
    return out


def divided_exp(a, b):
    """(e^a - e^b)/(a - b) = e^a phi1(b - a), taking a as the argument with the larger real part."""
    swap = a.real < b.real
    hi = np.where(swap, b, a)
    lo = np.where(swap, a, b)
    return np.exp(hi) * phi1(lo - hi)


def numpy_modal(s):
    """The modal closed form (simulation/modal_simulator.h), in NumPy: displacement output of a sin^2 pulse."""
    M, C, K = s["M"], s["C"], s["K"]
    f, c = s["load"], s["sensor"]
    n = M.shape[0]
    # Undamped modes: M phi = mu K phi (mu = 1/omega^2), phi^T M phi = 1.
    mu, y = scipy.linalg.eigh(M, K)
    shapes = y / np.sqrt(mu)
    mt = shapes.T @ M @ shapes
    kt = shapes.T @ K @ shapes
    ct = shapes.T @ C @ shapes
    d = np.sqrt(np.diag(kt))
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.diag(d)
    a[n:, :n] = -np.linalg.solve(mt, kt) / d
    a[n:, n:] = -np.linalg.solve(mt, ct)
    lam, v = np.linalg.eig(a)
    b = np.zeros(2 * n)
    b[n:] = np.linalg.solve(mt, shapes.T @ f)
    g = s["amplitude_N"] * np.linalg.solve(v, b)
    row = np.zeros(2 * n)
    row[:n] = (shapes.T @ c) / d
    h = v.T @ row
    keep = lam.imag >= 0
    lam, g, h = lam[keep], g[keep], h[keep]
    weight = np.where(lam.imag > 0, 2.0, 1.0)
    hg = (weight * h * g)[:, None]

    tau, dt, samples = s["pulse_width_s"], s["dt_s"], s["samples"]
    t = np.arange(samples) * dt
    inside = t <= tau
    w = 2 * np.pi / tau
    lt = lam[:, None] * t[None, inside]
    iwt = (1j * w * t[inside])[None, :]
    pulse = t[None, inside] * (0.5 * divided_exp(lt, np.zeros_like(lt)) - 0.25 *
                                (divided_exp(lt, np.broadcast_to(iwt, lt.shape)) +
                                 divided_exp(lt, np.broadcast_to(-iwt, lt.shape))))
    y_out = np.empty(samples)
    y_out[inside] = (hg * pulse).sum(axis=0).real
    at_tau = (tau * (0.5 * divided_exp(lam * tau, np.zeros_like(lam)) - 0.25 *
                     (divided_exp(lam * tau, np.full_like(lam, 1j * w * tau)) +
                      divided_exp(lam * tau, np.full_like(lam, -1j * w * tau)))))[:, None]
    y_out[~inside] = (hg * at_tau * np.exp(lam[:, None] * (t[None, ~inside] - tau))).sum(axis=0).real
    return y_out


def scipy_bdf(s, rtol=1e-8):
    """solve_ivp BDF on z = (w, w'), z' = J z + [0; M^-1 load] P(t), with the constant Jacobian J."""
    M, C, K = s["M"], s["C"], s["K"]
    n = M.shape[0]
    minv = np.linalg.inv(M)
    jac = np.zeros((2 * n, 2 * n))
    jac[:n, n:] = np.eye(n)
    jac[n:, :n] = -minv @ K
    jac[n:, n:] = -minv @ C
    b = np.zeros(2 * n)
    b[n:] = minv @ s["load"]
    tau, amplitude = s["pulse_width_s"], s["amplitude_N"]

    def rhs(t, z):
        p = amplitude * np.sin(np.pi * t / tau) ** 2 if t <= tau else 0.0
        return jac @ z + b * p

    # Natural sizes: the static deflection under the load, and that times the lowest frequency for velocities.
    static = np.linalg.solve(K, s["load"] * amplitude)
    omega1 = np.sqrt(np.min(np.linalg.eigvals(np.linalg.solve(M, K)).real))
    atol = np.concatenate([np.full(n, 1e-3 * np.max(np.abs(static))), np.full(n, omega1 * np.max(np.abs(static)))])
    t_eval = np.arange(s["samples"]) * s["dt_s"]
    sol = scipy.integrate.solve_ivp(rhs, (0.0, t_eval[-1]), np.zeros(2 * n), method="BDF", t_eval=t_eval, rtol=rtol,
                                    atol=rtol * atol, jac=jac, first_step=tau / 64)
    if not sol.success:
        raise RuntimeError("solve_ivp BDF: " + sol.message)
    return s["sensor"] @ sol.y[:n, :], sol.nfev


def time_beamid(bench):
    out = subprocess.run([bench, "--benchmark_filter=^BM_SimulateFastPeer$", "--benchmark_format=json",
                          "--benchmark_min_time=0.5"], check=True, capture_output=True, text=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b["name"] == "BM_SimulateFastPeer"]
    if not runs:
        raise RuntimeError(bench + ": no BM_SimulateFastPeer in its output")
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[runs[0]["time_unit"]]
    return runs[0]["real_time"] * unit


def time_call(f, budget_s=0.5):
    times = []
    start = time.perf_counter()
    while not times or time.perf_counter() - start < budget_s:
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--beamid", required=True, help="the beamid program")
    parser.add_argument("--bench", required=True, help="the beamid_bench program (Google Benchmark)")
    parser.add_argument("--output", required=True, help="peers.json to write")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()

    s = read_system(args.beamid)
    reference = beamid_trace(args.beamid)
    scale = np.max(np.abs(reference))
    y_numpy = numpy_modal(s)
    agreement = {"numpy-modal": float(np.max(np.abs(y_numpy - reference)) / scale)}

    rounds = []
    bdf = {}
    for r in range(args.rounds):
        t_beamid = time_beamid(args.bench)
        t_numpy = time_call(lambda: numpy_modal(s))
        row = {"beamid_s": t_beamid, "numpy_modal_s": t_numpy, "numpy_modal_over_beamid": t_numpy / t_beamid}
        line = (f"round {r + 1}/{args.rounds}: beamid {t_beamid * 1e3:.3f} ms, numpy-modal {t_numpy * 1e3:.3f} ms "
                f"({t_numpy / t_beamid:.1f}x)")
        if r == args.rounds // 2:
            t0 = time.perf_counter()
            y_bdf, bdf_rhs = scipy_bdf(s)
            t_bdf = time.perf_counter() - t0
            agreement["scipy-bdf"] = float(np.max(np.abs(y_bdf - reference)) / scale)
            bdf = {"scipy_bdf_s": t_bdf, "rhs_evaluations": int(bdf_rhs), "round": r + 1}
            row.update({"scipy_bdf_s": t_bdf, "scipy_bdf_over_beamid": t_bdf / t_beamid})
            line += f", scipy-bdf {t_bdf:.1f} s ({t_bdf / t_beamid:.0f}x)"
        rounds.append(row)
        print(line, flush=True)

    def median(key):
        return statistics.median(r[key] for r in rounds if key in r)

    result = {
        "computation": f"{BEAM}, N = {ELEMENTS} ({s['M'].shape[0]} DOF), sin^2 pulse 4 ms at 0.7 l, tip displacement, "
                       f"dt = 10 us, Nbar = {s['samples']}; one thread each",
        "beamid_benchmark": "BM_SimulateFastPeer (Google Benchmark real time)",
        "python": sys.version.split()[0], "numpy": np.__version__, "scipy": scipy.__version__,
        "max_abs_difference_over_max_abs_y": agreement,
        "scipy_bdf": bdf,
        "rounds": rounds,
        "median_s": {"beamid": median("beamid_s"), "numpy-modal": median("numpy_modal_s"),
                     "scipy-bdf (one run)": bdf["scipy_bdf_s"]},
        "median_ratio": {"numpy-modal/beamid": median("numpy_modal_over_beamid"),
                         "scipy-bdf/beamid": median("scipy_bdf_over_beamid")},
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output + ".tmp", "w") as out:
        json.dump(result, out, indent=2)
        out.write("\n")
    os.replace(args.output + ".tmp", args.output)
    print(f"peers: median ratios numpy-modal/beamid {result['median_ratio']['numpy-modal/beamid']:.1f}, "
          f"scipy-bdf/beamid {result['median_ratio']['scipy-bdf/beamid']:.0f}; agreement with beamid "
          f"{agreement['numpy-modal']:.1e} (numpy), {agreement['scipy-bdf']:.1e} (bdf) of max |y|; "
          f"written to {args.output}")


if __name__ == "__main__":
    main()
