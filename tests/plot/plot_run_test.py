#!/usr/bin/python3
"""tools/plot/plot_run.py on synthetic runs: every device figure (and its variants), a missing column, a
missing "limits" block, no report.json, a device without a plot module, and malformed CSVs.

Run: /usr/bin/python3 tests/plot/plot_run_test.py   (plain unittest; Debian's python3-matplotlib and numpy)
Each case writes signals.csv and report.json into a temporary directory. The refusals and the fall-backs run
plot_run.py as gyrostab does (/usr/bin/python3 SCRIPT DIR); the device figures run through plot_run.main in one
worker process (one interpreter and matplotlib start-up for all of them, which keeps the test well under a
minute on a busy machine). A figure must return 0, print nothing on stderr (GYROSTAB_PLOT_STRICT=1: a failing
device module is an error, not a silent fall-back to the generic figure) and write a PNG of about 12 in at
110 dpi with some content; a malformed CSV must exit non-zero with one line on stderr and no traceback.
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCRIPT = os.path.join(ROOT, "tools", "plot", "plot_run.py")
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
D = math.pi / 180


# ----------------------------------------------------------------------------------------- synthetic runs

def scene(device, duration, name=None, seed=1):
    return {"device": device, "duration_s": duration, "name": name or "synthetic-" + device, "seed": seed,
            "tick_ns": 1000000, "file": "synthetic.toml"}


def ship(law="active"):
    t = np.arange(1, 6001) * 0.05  # 300 s
    rng = np.random.default_rng(1)
    w = np.array([0.5, 0.6, 0.7])
    ph = rng.uniform(0, 2 * np.pi, 3)
    roll0 = sum(0.05 * np.sin(wi * t + p) for wi, p in zip(w, ph))
    roll = 0.2 * roll0
    prec = 1.0 * np.sin(0.6 * t + 1.0)
    torque = np.clip(8e4 * np.sin(0.6 * t + 2.0), -6e4, 6e4)
    status = np.where(np.abs(torque) >= 6e4, 1 << 21, 0) | np.where(np.abs(prec) > 60 * D, 1 << 22, 0)
    cols = {"roll_rad": roll, "roll_unstabilized_rad": roll0, "precession_rad": prec,
            "roll_rate_rad_s": np.gradient(roll, t), "precession_rate_rad_s": np.gradient(prec, t),
            "wave_moment_Nm": 4e5 * np.sin(0.6 * t), "precession_torque_Nm": torque, "status_bits": status}
    m = t >= 60
    figures = {"roll_rms_rad": float(np.sqrt(np.mean(roll[m] ** 2))),
               "roll_rms_unstabilized_rad": float(np.sqrt(np.mean(roll0[m] ** 2))), "roll_rms_ratio": 0.2, "roll_reduction": 0.8,
               "roll_max_rad": float(np.abs(roll[m]).max()), "roll_max_unstabilized_rad": float(np.abs(roll0[m]).max()),
               "precession_max_rad": 1.0, "precession_torque_max_Nm": 6e4, "wave_moment_rms_Nm": 2.8e5,
               "statistics_from_s": 60.0, "stop_penetration_max_rad": 0.0, "stop_penetration_bound_rad": 0.004}
    limits = {"precession_stop_rad": 70 * D, "precession_torque_limit_Nm": 2e5}
    if law == "active":
        limits["precession_soft_limit_rad"] = 60 * D
    report = {"scene": scene("ship_roll_damper", 300.0), "figures": figures, "limits": limits,
              "plant": {"components": ["ship roll + gyro case precession (14.8)", "irregular sea"]}}
    return cols, t, report


def power(variant="torque"):
    t = np.arange(1, 2001) * 0.005  # 10 s
    s1, s2 = (t >= 1.0), (t >= 3.0)
    w, sig = 115.0, 1.9
    nut = np.where(s1, 0.08 * np.exp(-sig * (t - 1)) * np.sin(w * (t - 1)), 0.0)
    beta = np.where(s1, 0.1 * (1 - np.exp(-(t - 1))), 0.0)
    alpha = np.where(s2, 0.05 * (1 - np.exp(-(t - 3))), 0.0) + 0.001 * nut
    cols = {"alpha_rad": alpha, "beta_rad": beta, "alpha_rate_rad_s": nut, "beta_rate_rad_s": np.gradient(beta, t),
            "M1_motor_Nm": -20 * beta / 0.1, "M2_motor_Nm": 10 * alpha / 0.05, "M1_disturbance_Nm": 20.0 * s1,
            "M2_disturbance_Nm": -10.0 * s2, "status_bits": np.zeros_like(t)}
    figures = {"nutation_frequency_rad_s": 115.6, "nutation_frequency_rad_s_predicted": 115.5,
               "nutation_decay_rate_per_s": 1.9, "nutation_decay_rate_per_s_predicted": 1.95,
               "steady_alpha_rad": 0.05, "steady_alpha_rad_predicted": 0.05, "steady_beta_rad": 0.1,
               "steady_beta_rad_predicted": 0.1, "motor1_torque_peak_Nm": 20.0, "motor2_torque_peak_Nm": 10.0}
    limits = {"motor_torque_limit_Nm": 100.0}
    plant = {"fidelity": "full", "components": ["gimbal gyro (10.4) with nutation"]}
    report = {"scene": scene("power_stabilizer", 10.0), "figures": figures, "limits": limits, "plant": plant}
    if variant == "dc":
        cols.update({"motor1_current_A": cols["M1_motor_Nm"] / 10, "motor2_current_A": cols["M2_motor_Nm"] / 10,
                     "motor1_voltage_V": 0.5 * np.sin(t), "motor2_voltage_V": 0.4 * np.cos(t)})
        limits.update({"drive_current_limit_A": 12.0, "drive_voltage_limit_V": 48.0})
        figures.update({"nutation_frequency_rad_s": None, "nutation_decay_rate_per_s": None,
                        "nutation_measurement": "not measured: stick-slip", "drive_peak_torque_Nm": 103.68})
    elif variant == "back_emf":
        cols["M2_motor_Nm"] = np.zeros_like(t)
        cols["motor1_voltage_V"] = 2.0 * beta
        report["limits"] = {"motor_voltage_limit_V": 24.0}
        figures.update({"steady_alpha_rad_predicted": None, "r_max_V_per_rad": 100.0})
    elif variant == "elastic":
        cols["platform_rad"] = 0.9 * alpha
        figures.update({"steady_platform_rad": 0.045, "platform_frequency_rad_s_predicted": 30.0})
    elif variant == "precession":
        plant["fidelity"] = "precession"
        figures.update({"nutation_frequency_rad_s": None, "nutation_decay_rate_per_s": None,
                        "nutation_measurement": "not measured: the precession model (P0) has no nutation"})
        report["reduced_model"] = {"epsilon": 0.0087, "alpha_rad_bound": 2.8e-3, "beta_rad_bound": 2.3e-3,
                                   "measured_error": {"alpha_rad_max": 1.4e-3, "beta_rad_max": 9.7e-4},
                                   "within_bounds": True}
    elif variant == "safe_state":
        cols["status_bits"] = np.full_like(t, (1 << 9) | (1 << 10) | (1 << 3))
        cols["M1_motor_Nm"] = np.zeros_like(t)
        cols["M2_motor_Nm"] = np.zeros_like(t)
    elif variant == "drift":  # the three-hour run: only alpha, beta recorded, a periodic-drift block
        t = np.arange(1, 3601) * 1.0
        cols = {"alpha_rad": 0.05 + 0.02 * np.sin(2 * np.pi * t / 10), "beta_rad": 0.1 + 1e-4 * np.cos(2 * np.pi * t / 10)}
        report["drift"] = {"period_ticks": 10000, "reference_from_s": 100.0, "bound_rad": 4.8e-5,
                           "compared_ticks": 3500000, "within_bound": True,
                           "max_departure": {"alpha_rad": 1e-7, "beta_rad": 8e-8}}
        report["scene"]["duration_s"] = 3600.0
    return cols, t, report


def monorail():
    t = np.arange(1, 6001) * 0.01
    gust = np.interp(t, [0, 10, 11, 22, 23, 60], [0, 0, 300, 300, 0, 0])
    om = np.interp(t, [0, 32, 35, 50, 53, 60], [0, 0, 0.03, 0.03, 0, 0])
    tilt = 0.026 * np.exp(-0.7 * t) * np.cos(3 * t) - 0.015 * gust / 300 - 0.015 * om / 0.03
    case = 0.16 * gust / 300 + 0.22 * om / 0.03
    cols = {"tilt_rad": tilt, "case_angle_rad": case, "tilt_rate_rad_s": np.gradient(tilt, t),
            "case_rate_rad_s": np.gradient(case, t), "Omega3_rad_s": om, "gust_moment_Nm": gust,
            "centrifugal_moment_Nm": 305 * om / 0.03, "motor_torque_Nm": 5500 * tilt, "status_bits": np.zeros_like(t)}
    figures = {"statistics_from_s": 8.0, "tilt_rms_rad": 0.011, "tilt_max_rad": 0.017, "case_angle_max_rad": 0.225,
               "motor_torque_max_Nm": 145.0, "k_Nm_per_rad": 5500.0, "k_lo_Nm_per_rad": 1112.0,
               "k_hi_Nm_per_rad": 14388.0, "gust_lean_rad": -0.015, "gust_lean_rad_predicted": -0.015,
               "curve_lean_rad": -0.0154, "curve_lean_rad_predicted": -0.0154, "overturned": False,
               "overturned_at_s": None, "curve_radius_m": 166.7, "curve_Omega3_rad_s": 0.03}
    return cols, t, {"scene": scene("monorail", 60.0), "figures": figures, "limits": {"motor_torque_limit_Nm": 2000.0}}


def servo():
    t = np.arange(1, 3001) * 0.01
    rate = np.minimum(10.0, 10.0 * t)
    alpha = 0.0995 * np.sin(10 * t) * (1 - np.exp(-2.5 * t))
    cols = {"alpha_rad": alpha, "alpha_rate_rad_s": np.gradient(alpha, t), "drive_rate_rad_s": rate,
            "M1_gyro_Nm": -10 * np.cos(10 * t), "motor_torque_Nm": np.where(t < 1, 5.0, 0.5 + 0.5 * np.sin(20 * t)),
            "status_bits": np.where(t < 1, 1 << 24, 0)}
    figures = {"alpha_A_rad": 0.0995, "phase_rad": -1.5708, "M1_max_Nm": 10.0, "M2_max_Nm": 1.01, "torque_gain": 9.86,
               "torque_gain_book": 10.05, "torque_gain_harmonic": 10.05, "drive_rate_reference_rad_s": 10.0,
               "drive_rate_mean_rad_s": 10.0, "drive_rate_error_max_rad_s": 1.5e-4, "motor_power_W": 4.975,
               "dissipation_W": 4.975, "revolutions": 28, "statistics_from_s": 12.0}
    return cols, t, {"scene": scene("servo_gyro", 30.0), "figures": figures, "limits": {"motor_torque_limit_Nm": 5.0}}


def gyro_vertical():
    t = np.arange(1, 9001) * 0.1
    turn = np.where((t > 300) & (t <= 540), 0.026, 0.0) - np.where(t > 720, 0.026, 0.0)
    aL = np.arctan(120 * turn / 9.81)
    a = np.convolve(aL, np.ones(500) / 500, mode="same") * 0.4
    cols = {"alpha_rad": a, "beta_rad": -0.5 * a, "alpha_L_rad": aL, "beta_L_rad": np.zeros_like(t),
            "M1_Nm": 0.01 * a, "M2_Nm": -0.01 * a, "turn_rate_rad_s": turn, "turn_indicator_rad_s": 0.95 * turn,
            "status_bits": np.zeros_like(t)}
    segs = [{"segment": i + 1, "t_start_s": t0, "t_end_s": t1, "turn_rate_rad_s": w, "alpha_end_rad": 0.1,
             "alpha_book_end_rad": 0.1, "beta_end_rad": -0.05, "beta_book_end_rad": -0.05, "alpha_G_rad": 0.1,
             "beta_G_rad": -0.05, "correction_cut_out": False, "turn_indicator_over_true": 0.95}
            for i, (t0, t1, w) in enumerate([(0, 300, 0.0), (300, 540, 0.026), (540, 720, 0.0), (720, 900, -0.026)])]
    figures = {"indicated_bank_error_max_rad": float(np.abs(a).max()), "delta_s": 0.02, "omega_P_rad_s": 0.005,
               "prediction_applies": True, "segments": segs}
    limits = {"torquer_limit_Nm": 0.01, "turn_cutout_rad_s": 0.5 * D}
    return cols, t, {"scene": scene("gyro_vertical", 900.0), "figures": figures, "limits": limits}


def gyrocompass(moving=False):
    if not moving:
        t = np.arange(1, 28801) * 1.0
        aeq = np.full_like(t, -0.027)
        a = aeq + 0.087 * np.exp(-3.7e-4 * t) * np.cos(2 * np.pi * t / 5300)
        lat, hdg = np.full_like(t, 50.0), np.zeros_like(t)
        figures = {"period_measured_s": 5310.0, "period_book_13_12_s": 5304.0, "decay_rate_measured_s": 3.7e-4,
                   "decay_rate_book_13_12_s": 3.7e-4, "alpha_eq_measured_rad": -0.027, "alpha0_book_13_11_rad": -0.027,
                   "beta0_book_13_11_rad": 0.0017}
    else:
        t = np.arange(1, 7501) * 10.0
        aeq = np.where((t > 10800) & (t < 15000), 0.0, -0.05)
        a = aeq + 2e-4 * np.sin(2 * np.pi * t / 4741)
        lat = np.interp(t, [0, 10800, 15000, 65400, 75000], [51.5, 50, 50, 43, 43])
        hdg = np.full_like(t, 180.0)
        figures = {"period_measured_s": 4723.0, "period_book_13_12_s": 4741.0, "decay_rate_book_13_12_s": 0.0,
                   "tune_latitude_deg": 50.0,
                   "segments": [{"t_start_s": 0.0, "t_end_s": 10800.0, "deviation_from_equilibrium_max_rad": 2e-4},
                                {"t_start_s": 10800.0, "t_end_s": 11100.0, "deviation_from_equilibrium_max_rad": 7e-5},
                                {"t_start_s": 11100.0, "t_end_s": 75000.0, "deviation_from_equilibrium_max_rad": 2e-4}]}
    b = 0.0017 + 0.001 * (a - aeq) / 0.087
    cols = {"alpha_rad": a, "beta_rad": b, "alpha_eq_rad": aeq, "level_rad": b, "M1_Nm": -2e-5 * (a - aeq),
            "M2_Nm": np.zeros_like(t), "latitude_deg": lat, "heading_deg": hdg, "swing_rad": np.zeros_like(t),
            "status_bits": np.zeros_like(t)}
    return cols, t, {"scene": scene("gyrocompass", float(t[-1])), "figures": figures, "limits": {"torquer_limit_Nm": 0.05}}


def inertial(axes=3):
    t = np.arange(1, 2161) * 5.0
    T = 5063.5
    e1 = 1.745e-4 * np.cos(2 * np.pi * t / T)
    v1 = -1.38 * np.sin(2 * np.pi * t / T)
    th = np.where((t > 600) & (t < 700), 0.25, 0.0)
    cols = {"tilt1_rad": e1, "tilt2_rad": (1e-7 if axes == 3 else 0.0) * np.sin(t / 800), "theta1_rad": th,
            "theta2_rad": 0.5 * th if axes == 3 else np.zeros_like(t), "torquer1_Nm": 1e-6 * np.sin(t / 800),
            "torquer2_Nm": np.zeros_like(t), "gyro1_rad": np.full_like(t, 6.67e-3), "velocity_error1_m_s": v1,
            "status_bits": np.zeros_like(t)}
    ch = [{"channel": 1, "period_measured_s": 5066.0, "period_loop_book_s": T, "tilt_max_rad": 1.745e-4,
           "tilt_bound_tuned_rad": 1.745e-4, "velocity_error_max_m_s": 1.38,
           "velocity_error_amplitude_book_16_47_m_s": 1.38, "position_error_max_m": 2222.0,
           "position_error_max_book_16_47_m": 2224.0, "servo_offset_book_16_2_rad": 6.67e-3}]
    if axes == 3:
        ch.append({"channel": 2, "period_measured_s": None, "tilt_max_rad": 4e-7})
    figures = {"axes": axes, "schuler_period_s": T, "channels": ch}
    return cols, t, {"scene": scene("inertial_platform", 10800.0), "figures": figures,
                     "limits": {"torquer_limit_Nm": 0.01}}


def pendulum():
    t = np.arange(1, 1081) * 10.0
    ab = -0.03 - 0.02 * np.sin(t / 2000)
    bb = 0.01 * np.cos(t / 1500)
    p = 1.7e-5 + 1e-6 * np.sin(t / 900)
    cols = {"alpha_rad": ab + 1.7e-5 * np.cos(2 * np.pi * t / 5064), "beta_rad": bb + 1.7e-5 * np.sin(2 * np.pi * t / 5064),
            "tilt_rad": np.hypot(ab, bb), "alpha_book_rad": ab, "beta_book_rad": bb, "precession_mode_rad": p,
            "speed_m_s": np.interp(t, [0, 600, 700, 9300, 9400, 10800], [0, 0, 200, 200, 0, 0]),
            "heading_deg": np.interp(t, [0, 2500, 2600, 10800], [60, 60, 150, 150]), "latitude_deg": 50 + t / 3000,
            "status_bits": np.zeros_like(t)}
    figures = {"vertical_error_max_rad": 0.065, "book_velocity_error_max_rad": 0.065,
               "deviation_from_book_max_rad": 2.4e-5, "precession_mode_start_rad": 1.7e-5,
               "precession_mode_min_rad": 1.6e-5, "precession_mode_max_rad": 1.9e-5, "precession_mode_end_rad": 1.7e-5,
               "nutation_ripple_max_rad": 6.8e-6, "period_measured_min": 84.47, "period_book_min": 84.39,
               "schuler_period_book_min": 84.39, "nutation_frequency_rad_s": 250.0, "model": "magnus"}
    return cols, t, {"scene": scene("gyro_pendulum", 10800.0), "figures": figures}


# --------------------------------------------------------------------------------------------- harness

def write_run(d, cols, t, report, drop=(), limits=True):
    os.makedirs(d, exist_ok=True)
    names = [n for n in cols if n not in drop]
    data = np.column_stack([t] + [np.asarray(cols[n], dtype=float) * np.ones_like(t) for n in names])
    with open(os.path.join(d, "signals.csv"), "w") as f:
        f.write(",".join(["t_s"] + names) + "\n")
        np.savetxt(f, data, delimiter=",", fmt="%.17g")
    if report is not None:
        report = json.loads(json.dumps(report, default=float))
        if not limits:
            report.pop("limits", None)
        with open(os.path.join(d, "report.json"), "w") as f:
            json.dump(report, f)


def run_plot(d, strict=True):
    env = dict(os.environ, GYROSTAB_PLOT_STRICT="1" if strict else "0")
    return subprocess.run([PYTHON, SCRIPT, d], capture_output=True, text=True, env=env, timeout=60)


# plot_run.main on many directories in one process; prints {dir: [returncode, stderr]} as JSON.
WORKER = r"""
import contextlib, io, json, sys, traceback
sys.path.insert(0, sys.argv[1])
import plot_run
out = {}
for d in json.load(open(sys.argv[2])):
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            rc = plot_run.main(["plot_run.py", d])
    except BaseException:
        rc, err = 99, io.StringIO(traceback.format_exc())
    out[d] = [rc, err.getvalue()]
print(json.dumps(out))
"""


def run_plots_in_one_process(dirs, tmp):
    lst = os.path.join(tmp, "dirs.json")
    with open(lst, "w") as f:
        json.dump(dirs, f)
    env = dict(os.environ, GYROSTAB_PLOT_STRICT="1")
    r = subprocess.run([PYTHON, "-c", WORKER, os.path.dirname(SCRIPT), lst], capture_output=True, text=True, env=env,
                       timeout=300)
    if r.returncode != 0:
        raise AssertionError("plot worker failed: %s" % r.stderr)
    return {d: subprocess.CompletedProcess([SCRIPT, d], rc, "", err) for d, (rc, err) in json.loads(r.stdout).items()}


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        raise AssertionError("%s is not a PNG" % path)
    return struct.unpack(">II", head[16:24])


CASES = {
    "ship_active": (ship, ("active",), {}),
    "ship_passive": (ship, ("passive",), {}),
    "ship_missing_columns": (ship, (), {"drop": ("roll_unstabilized_rad", "wave_moment_Nm", "precession_torque_Nm")}),
    "ship_missing_limits": (ship, (), {"limits": False}),
    "power_torque": (power, ("torque",), {}),
    "power_dc": (power, ("dc",), {}),
    "power_back_emf": (power, ("back_emf",), {}),
    "power_elastic": (power, ("elastic",), {}),
    "power_precession": (power, ("precession",), {}),
    "power_safe_state": (power, ("safe_state",), {}),
    "power_drift_two_columns": (power, ("drift",), {}),
    "power_missing_limits": (power, ("dc",), {"limits": False, "drop": ("motor2_voltage_V", "beta_rate_rad_s")}),
    "monorail": (monorail, (), {}),
    "monorail_missing": (monorail, (), {"drop": ("case_angle_rad", "gust_moment_Nm"), "limits": False}),
    "servo_gyro": (servo, (), {}),
    "servo_gyro_missing": (servo, (), {"drop": ("drive_rate_rad_s", "M1_gyro_Nm"), "limits": False}),
    "gyro_vertical": (gyro_vertical, (), {}),
    "gyro_vertical_missing": (gyro_vertical, (), {"drop": ("turn_rate_rad_s", "turn_indicator_rad_s", "M1_Nm", "M2_Nm"),
                                                  "limits": False}),
    "gyrocompass_fixed": (gyrocompass, (False,), {}),
    "gyrocompass_moving": (gyrocompass, (True,), {"limits": False}),
    "gyrocompass_missing": (gyrocompass, (False,), {"drop": ("alpha_eq_rad", "beta_rad", "level_rad")}),
    "inertial_3axis": (inertial, (3,), {}),
    "inertial_1axis_missing": (inertial, (1,), {"drop": ("velocity_error1_m_s",), "limits": False}),
    "gyro_pendulum": (pendulum, (), {}),
    "gyro_pendulum_missing": (pendulum, (), {"drop": ("alpha_book_rad", "beta_book_rad", "speed_m_s")}),
}


class PlotRunTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="plot_run_test_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def assert_figure(self, d, r):
        self.assertEqual(r.returncode, 0, "%s: exit %d, stderr: %s" % (d, r.returncode, r.stderr))
        self.assertEqual(r.stderr.strip(), "", "%s: stderr not empty" % d)
        png = os.path.join(d, "signals.png")
        self.assertTrue(os.path.isfile(png), "%s: no signals.png" % d)
        w, h = png_size(png)
        self.assertTrue(1200 <= w <= 1450, "%s: width %d px, want ~12 in at 110 dpi" % (d, w))
        self.assertTrue(400 <= h <= 1700, "%s: height %d px" % (d, h))
        self.assertGreater(os.path.getsize(png), 30000, "%s: PNG too small to hold a figure" % d)

    def assert_refused(self, d, what):
        r = run_plot(d)
        self.assertNotEqual(r.returncode, 0, "%s: %s accepted" % (d, what))
        lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
        self.assertEqual(len(lines), 1, "%s: want one line on stderr, got: %r" % (d, r.stderr))
        self.assertNotIn("Traceback", r.stderr)
        self.assertTrue(lines[0].startswith("plot_run.py: "), lines[0])
        self.assertFalse(os.path.exists(os.path.join(d, "signals.png")))

    def test_device_figures(self):
        dirs = {}
        for name, (make, args, kw) in CASES.items():
            d = os.path.join(self.tmp, name)
            cols, t, report = make(*args)
            write_run(d, cols, t, report, **kw)
            dirs[name] = d
        results = run_plots_in_one_process(list(dirs.values()), self.tmp)
        for name, d in dirs.items():
            with self.subTest(case=name):
                self.assert_figure(d, results[d])

    def test_device_figure_through_the_command_line(self):
        d = os.path.join(self.tmp, "cli_ship")
        cols, t, report = ship()
        write_run(d, cols, t, report)
        self.assert_figure(d, run_plot(d))

    def test_a_megabyte_scene_name_is_shortened_in_the_title(self):
        # A scene file may be 1 MiB, its name nearly all of it: laid out whole as a title it took matplotlib
        # 754 MB and then failed. The title keeps the first 80 characters; the figure is drawn as usual.
        d = os.path.join(self.tmp, "long_name")
        cols, t, report = monorail()
        report["scene"]["name"] = "n" * 1000000
        write_run(d, cols, t, report)
        r = subprocess.run([PYTHON, "-c", "import resource, subprocess, sys\n"
                            "p = subprocess.run(sys.argv[1:])\n"
                            "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
                            "sys.exit(p.returncode)", PYTHON, SCRIPT, d],
                           capture_output=True, text=True, env=dict(os.environ, GYROSTAB_PLOT_STRICT="1"), timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        peak_mb = int(r.stdout.split()[-1]) / 1024.0
        self.assertLess(peak_mb, 400.0, "the plot helper's peak resident memory")
        self.assertTrue(os.path.exists(os.path.join(d, "signals.png")))

    def test_no_report_draws_the_generic_figure(self):
        d = os.path.join(self.tmp, "no_report")
        cols, t, _ = monorail()
        write_run(d, cols, t, None)
        self.assert_figure(d, run_plot(d))

    def test_unknown_device_draws_the_generic_figure(self):
        d = os.path.join(self.tmp, "unknown_device")
        cols, t, report = servo()
        report["scene"]["device"] = "../../etc"  # not a device name: never a path
        write_run(d, cols, t, report)
        self.assert_figure(d, run_plot(d))

    def test_malformed_csv_is_refused_with_one_line(self):
        good = "t_s,roll_rad,status_bits\n0.05,0.01,0\n0.10,0.02,0\n"
        bad = {
            "ragged_row": good + "0.15,0.03\n",
            "not_a_number": good + "0.15,abc,0\n",
            "header_only": "t_s,roll_rad\n",
            "empty": "",
            "no_time_column": "roll_rad,status_bits\n0.01,0\n",
            "time_backwards": "t_s,roll_rad\n0.2,0.0\n0.1,0.0\n",
            "binary": None,
        }
        for name, text in bad.items():
            with self.subTest(case=name):
                d = os.path.join(self.tmp, "bad_" + name)
                os.makedirs(d, exist_ok=True)
                with open(os.path.join(d, "signals.csv"), "wb") as f:
                    f.write(b"\x89\xff\x00\x01garbage" if text is None else text.encode())
                with open(os.path.join(d, "report.json"), "w") as f:
                    json.dump({"scene": scene("ship_roll_damper", 1.0)}, f)
                self.assert_refused(d, name)

    def test_missing_directory_and_csv_are_refused(self):
        self.assert_refused(os.path.join(self.tmp, "does_not_exist"), "a missing directory")
        d = os.path.join(self.tmp, "no_csv")
        os.makedirs(d, exist_ok=True)
        self.assert_refused(d, "a directory without signals.csv")

    def test_no_device_column_draws_the_generic_figure(self):
        d = os.path.join(self.tmp, "only_status")
        cols, t, report = ship()
        write_run(d, cols, t, report, drop=[n for n in cols if n != "status_bits"])
        r = run_plot(d, strict=False)
        self.assert_figure(d, r)
        r = run_plot(d, strict=True)
        self.assertEqual(r.returncode, 0)
        self.assertIn("generic figure", r.stderr)

    def test_malformed_report_draws_the_generic_figure(self):
        d = os.path.join(self.tmp, "bad_report")
        cols, t, report = ship()
        write_run(d, cols, t, report)
        with open(os.path.join(d, "report.json"), "w") as f:
            f.write("{not json")
        self.assert_figure(d, run_plot(d))


if __name__ == "__main__":
    unittest.main(verbosity=2)
