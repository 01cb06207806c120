"""Wall time of a co-running fit at one position (issue 16 goal: within a minute on one core).

Run: ``python benchmarks/bench_fit.py``. BLAS and OpenMP are limited to one thread before
numpy loads, so the fit runs on one core. The FE reference receptances (full mesh,
``FEOptions()``, 400 frequencies 1-2000 Hz) are computed first and timed apart: the goal is
the fit. Cases: the report's switch and crossing receptance points, the loaded rail r2 alone
and every active rail of the zone (what ``exudyn-turnout fit`` does), 3 layers.
Prints a table: case, targets, free parameters, residual evaluations, FE time, fit time,
worst range band RMS vs FE (pinned-pinned bands left out) derived -> fitted. Each fit
alternates with the yardstick (``benchmarks/yardstick.py``): "fit yst" is the fit's wall
time in yardstick units (they carry over between machines and loads).
"""

import os

for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_name] = "1"

import time  # noqa: E402

from yardstick import Yardstick, machine_line  # noqa: E402

from exudyn_turnout.cli.fit import fe_fit_targets  # noqa: E402
from exudyn_turnout.corunning.fit import fit_position  # noqa: E402
from exudyn_turnout.corunning.parameters import co_running_parameters  # noqa: E402
from exudyn_turnout.inputs.turnout import load_turnout  # noqa: E402
from exudyn_turnout.receptance import log_frequencies  # noqa: E402

POINTS = (("switch", 3.889), ("crossing", 47.165))  # m, validation report receptance points
RANGES = ((1.0, 125.0), (125.0, 500.0), (500.0, 2000.0))


def main() -> None:
    turnout = load_turnout()
    f = log_frequencies(1.0, 2000.0, 400)
    print(
        f"{'case':<28} {'targets':>7} {'free':>5} {'nfev':>5} {'FE s':>7} {'fit s':>7} "
        f"{'fit yst':>8} {'worst dB derived -> fitted':>28}"
    )
    stick = Yardstick()
    for label, x in POINTS:
        zone = turnout.zone_at(x)
        t0 = time.perf_counter()
        all_targets, _ = fe_fit_targets(turnout, zone, [x], f)
        fe_time = time.perf_counter() - t0
        params = co_running_parameters(turnout, x=x, layers=3)
        for rails in (("r2",), zone.active_rails):
            targets = [t for t in all_targets[0] if t.rail in rails]
            timing = stick.measure(
                lambda params=params, x=x, targets=targets: fit_position(params, x, targets),
                repeats=1,
                warm_up=False,
            )
            fit, fit_time = timing.result, timing.seconds
            worst = {
                flag: max(r.range_rms(lo, hi, flag) for r in fit.residuals for lo, hi in RANGES)
                for flag in (False, True)
            }
            case = f"{label} x={x:g} m, {' '.join(rails)}"
            print(
                f"{case:<28} {len(targets):>7} {len(fit.free):>5} {fit.nfev:>5} "
                f"{fe_time:>7.1f} {fit_time:>7.1f} {timing.units:>8.1f} "
                f"{worst[False]:>15.1f} -> {worst[True]:.1f}"
            )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
