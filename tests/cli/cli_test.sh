#!/usr/bin/env bash
# Command-line cases run by CTest: cli_test.sh TURBODYN SOURCE_DIR WORK_DIR CASE
# Each case runs the program as a user would and checks exit code, files and messages.
set -u
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cli_setup "" "$@"

case $case in
  check_example)
    "$exe" check "$src/examples/reference_linear.toml" > "$out/log" 2>&1 || fail "exit $?"
    grep -q "rotor mass      0.45" "$out/log" || fail "no summary: $(cat "$out/log")"
    ;;
  bad_model_file)
    "$exe" check "$src/tests/data/bad_models/typo_key.toml" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "exit $rc, expected 2"
    grep -q "typo_key.toml:8:1: shaft\[0\].outer_diamter: unknown key; did you mean 'outer_diameter'?" "$out/log" \
      || fail "message: $(cat "$out/log")"
    ;;
  bad_override)
    "$exe" modal "$src/examples/reference_linear.toml" --set bearings.compressor.kxz=1 -o "$out" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "exit $rc, expected 2"
    grep -q "did you mean 'kxx'" "$out/log" || fail "message: $(cat "$out/log")"
    ;;
  modal_friswell)
    "$exe" modal "$src/examples/friswell_5_9_1.toml" -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" modal.json campbell.csv campbell.png modes_0rpm.png
    ;;
  modal_reference)
    "$exe" modal "$src/examples/reference_linear.toml" -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    grep -q "1x  forward branch 1" "$out/log" || fail "no critical speeds: $(cat "$out/log")"
    ;;
  response_reference)
    "$exe" response "$src/examples/reference_linear.toml" -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" response.csv response.json response.png response_phase.png
    grep -q "disk compressor: 511.7 Hz (30703 rpm)" "$out/log" || fail "listing: $(cat "$out/log")"
    # Each forward 1x critical of turbodyn modal is a resonance of the wheel that moves most in it, within 0.05 % of
    # the speed, and the amplification factor measured on the response is the one modal gives from the mode's damping
    # ratio zeta and the slope s = d f_n / d f_d of its branch: the response ~ 1 / (f_n(f_d) - f_d + i zeta f_n), so
    # the half-power band in rotor speed is 2 zeta f_c / (1 - s) and AF = (1 - s) / (2 zeta) to first order. The
    # linear bearings' forward branches rise (s = 0.07-0.08, gyroscopic stiffening); the ball bearings' fall (their
    # contacts soften with speed, s = -0.14 and -0.18), and their modes have zeta of about 1e-4: bands of 0.1-0.2 Hz,
    # between speeds 12.5 Hz apart, measured on the response itself.
    for model in reference_linear reference_ball; do
      "$exe" modal "$src/examples/$model.toml" --no-plots -o "$out/modal_$model" > "$out/modal.log" 2>&1 \
        || fail "modal $model: $(cat "$out/modal.log")"
      "$exe" response "$src/examples/$model.toml" --no-plots -o "$out/response_$model" > "$out/response.log" 2>&1 \
        || fail "response $model: $(cat "$out/response.log")"
      python3 - "$out/response_$model/response.json" "$out/modal_$model/modal.json" "$model" <<'EOF2' \
        || fail "resonances of $model"
import json, sys
res = json.load(open(sys.argv[1]))["resonances"]
crit = [c for c in json.load(open(sys.argv[2]))["critical_speeds"] if c["order"] == 1.0 and c["whirl"] == "forward"]
slopes = {"reference_linear": (0.05, 0.1), "reference_ball": (-0.2, -0.1)}[sys.argv[3]]
assert len(crit) == 2, crit
for c in crit:
    near = [r for r in res if abs(r["speed_rpm"] / c["speed_rpm"] - 1) < 5e-4]
    assert near, (c, res)
    r = max(near, key=lambda r: r["peak"])
    s, expected, af = c["branch_slope"], c["amplification_factor"], r["amplification_factor"]
    assert abs(expected - (1 - s) / (2 * c["damping_ratio"])) < 1e-9 * expected, c
    assert slopes[0] < s < slopes[1] and abs(af / expected - 1) < 1e-3, (c, r)  # measured: 2e-5
    assert r["lower_speed_hz"] < r["speed_hz"] < r["upper_speed_hz"], r
    print(f'{sys.argv[3]} {c["speed_rpm"]:.0f} rpm: AF {af:.1f} measured, {expected:.1f} from zeta and s = {s:.4f}')
EOF2
    done
    # The run-up itself: at the paper's ramp each forward critical is passed late and low, where and as high as modal's
    # passage of the mode predicts (runup_peak_speed_rpm, runup_peak_fraction of the steady resonance that turbodyn
    # response measures): the turbine wheel peaks at the first (31,967 rpm predicted), the compressor wheel at the
    # second (43,236 rpm), 3-4 % above the critical speeds, with 0.23 and 0.33 of their steady peaks.
    "$exe" run "$src/examples/reference_linear.toml" --no-plots -o "$out/run" > "$out/run.log" 2>&1 \
      || fail "run: $(cat "$out/run.log")"
    python3 - "$out/run/summary.json" "$out/modal_reference_linear/modal.json" \
      "$out/response_reference_linear/response.json" <<'EOF2' || fail "run-up passages"
import json, sys
probes = json.load(open(sys.argv[1]))["probes"]
crit = [c for c in json.load(open(sys.argv[2]))["critical_speeds"] if c["order"] == 1.0 and c["whirl"] == "forward"]
res = json.load(open(sys.argv[3]))["resonances"]
for c, wheel in zip(crit, ("turbine", "compressor")):
    run = probes[f"disk.{wheel}.x"]
    steady = [r for r in res if r["column"] == f"disk.{wheel}.major_semi_axis_m"
              and abs(r["speed_rpm"] / c["speed_rpm"] - 1) < 5e-4][0]["peak"]
    # measured: 0.09 % and 0.10 % in speed, 0.07 % and 0.6 % in height
    assert abs(run["speed_at_max_rpm"] / c["runup_peak_speed_rpm"] - 1) < 0.003, (run, c)
    assert abs(run["max_abs"] / (c["runup_peak_fraction"] * steady) - 1) < 0.015, (run, c, steady)
    assert run["speed_at_max_rpm"] > 1.03 * c["speed_rpm"], (run, c)
    print(f'{wheel}: run peak {run["max_abs"] * 1e6:.1f} um at {run["speed_at_max_rpm"]:.0f} rpm, predicted '
          f'{c["runup_peak_fraction"] * steady * 1e6:.1f} um at {c["runup_peak_speed_rpm"]:.0f} rpm')
EOF2
    ;;
  response_nonlinear)
    # turbodyn response --nonlinear: the steady state on the ball bearings' quasi-static reaction, traced through its
    # folds (model/engine/unbalance_whirl.h). Variant II's first forward critical softens and then hardens: its
    # curve turns back at 496 Hz (a slow run-up jumps there) and forward again at 460 Hz (a slow run-down does).
    "$exe" response "$src/examples/reference_ball.toml" --speeds "10000 rpm:60000 rpm:51" --nonlinear \
      -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" response.csv response.json response_nonlinear.csv response.png report.html
    grep -q "fold at 2978[0-9] rpm (496.[0-9] Hz), largest wheel whirl 13.[0-9]* um: the speed turns back" "$out/log" \
      || fail "first fold: $(cat "$out/log")"
    head -1 "$out/response_nonlinear.csv" | grep -q "^piece,direction,speed_rad_s,speed_hz,stable,divergence_rate_1_s,disk.compressor.radius_m" \
      || fail "csv: $(head -1 "$out/response_nonlinear.csv")"
    grep -q 'data-table="nonlinear_folds"' "$out/report.html" || fail "report without the folds"
    python3 - "$out/response.json" <<'EOF2' || fail "response.json nonlinear"
import json, sys
nl = json.load(open(sys.argv[1]))["nonlinear"]
assert nl["covers_range"], nl.keys()
up = nl["pieces"][0]
assert up["direction"] == "up" and [f["kind"] for f in up["folds"]][:2] == ["turns back", "turns forward"], up["folds"]
assert 455 < up["folds"][1]["speed_hz"] < 465, up["folds"][1]
c = up["columns"]
assert len(c["speed_hz"]) == len(c["disk.turbine.radius_m"]) == len(c["bearing.turbine.force_n"]) > 50
# Between the two folds the branch is unstable (a real eigenvalue), before the first it is stable.
assert c["stable"][0] and not all(c["stable"]), c["stable"]
EOF2
    # The largest contact pressure of each steady state is Hertz's p0 of its largest contact load: between the outer
    # and the inner contact's p0 / Q^(1/3) (turbodyn bearing gives both per ball), and over ISO 76's limit it is warned
    # of (the resonances' whirl loads the balls with up to 1.5 kN).
    grep -q "warning: the nonlinear response passes the contact pressure's limit of 4200 MPa in bearings.compressor" \
      "$out/log" || fail "no contact pressure warning: $(cat "$out/log")"
    grep -q "<li>the nonlinear response passes the contact pressure" "$out/report.html" \
      || fail "report without the pressure warning"
    for name in compressor turbine; do
      "$exe" bearing "$src/examples/reference_ball.toml" --bearing $name --speeds "30000 rpm" --no-plots \
        -o "$out/bearing_$name" > "$out/bearing.log" 2>&1 || fail "bearing $name: $(cat "$out/bearing.log")"
    done
    python3 - "$out/response.json" "$out" <<'EOF2' || fail "contact pressures"
import json, sys
nl = json.load(open(sys.argv[1]))["nonlinear"]
assert len(nl["warnings"]) == 2, nl["warnings"]
for name in ("compressor", "turbine"):
    ball = json.load(open(f"{sys.argv[2]}/bearing_{name}/bearing.json"))["results"][0]["balls"][0]
    c_in = ball["inner_pressure_pa"] / ball["inner_load_n"] ** (1 / 3)
    c_out = ball["outer_pressure_pa"] / ball["outer_load_n"] ** (1 / 3)
    assert c_out < c_in, (c_out, c_in)
    for piece in nl["pieces"]:
        c = piece["columns"]
        for q, p in zip(c[f"bearing.{name}.max_contact_load_n"], c[f"bearing.{name}.max_contact_pressure_pa"]):
            assert c_out * q ** (1 / 3) * (1 - 1e-9) <= p <= c_in * q ** (1 / 3) * (1 + 1e-9), (name, q, p)
EOF2
    # A hundred times the paper's unbalance: the curves from both ends climb their resonances beyond Hertz theory,
    # which leaves the speeds between them without a steady state: written so far, exit code 3.
    "$exe" response "$src/examples/reference_ball.toml" --speeds "10000 rpm:80000 rpm:15" --nonlinear --no-plots \
      --set "disks.compressor.unbalance=39000 mg*mm" --set "disks.turbine.unbalance=58000 mg*mm" \
      -o "$out/gap" > "$out/gap.log" 2>&1
    [ $? -eq 3 ] || fail "exit $? for a gap: $(cat "$out/gap.log")"
    grep -q "leaves part of the speed range without a steady state" "$out/gap.log" || fail "$(cat "$out/gap.log")"
    python3 -c "import json,sys; n=json.load(open(sys.argv[1]))['nonlinear']; assert not n['covers_range'] and not n['pieces'][0]['complete']" \
      "$out/gap/response.json" || fail "gap not marked"
    # No range of speeds to follow.
    "$exe" response "$src/examples/reference_ball.toml" --speeds "0" --nonlinear --no-plots -o "$out/one" \
      > "$out/one.log" 2>&1
    [ $? -eq 2 ] && grep -q -- "--speeds '0': --nonlinear needs a range of speeds above zero" "$out/one.log" \
      || fail "single speed: $(cat "$out/one.log")"
    # What it cannot take: a ball bearing in a squeeze-film damper.
    "$exe" response "$src/examples/reference_ball_sfd.toml" --speeds "10000 rpm:30000 rpm:5" --nonlinear --no-plots \
      -o "$out/sfd" > "$out/sfd.log" 2>&1
    [ $? -eq 2 ] || fail "exit $? for a damper: $(cat "$out/sfd.log")"
    grep -q "reference_ball_sfd.toml: bearings.compressor.damper: squeeze-film dampers are nonlinear" \
      "$out/sfd.log" || fail "damper message: $(cat "$out/sfd.log")"
    ;;
  run_short)
    "$exe" run "$src/examples/reference_linear.toml" --set "speed.end=40000 rpm" --set speed.duration=0.5 \
      -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    grep -q '"complete": true' "$out/summary.json" || fail "summary not complete"
    expect_files "$out" timeseries.h5 spectrogram_disk.compressor.x.png order1x_disk.compressor.png \
      orbits_disk.compressor.png
    grep -q "largest sub-synchronous line at the end, disk.compressor.x: .* Hz (0\.[0-9]*x)" "$out/log" ||
      fail "no sub-synchronous line in the output: $(cat "$out/log")"
    # The largest spectral line of each spectrogram drawn: here the vibration at the first forward natural
    # frequency (512 Hz in the Campbell diagram) while and just after the rotor passes it.
    python3 - "$out/summary.json" <<'EOF2' || fail "spectrogram_maxima: $(grep -A3 spectrogram_maxima "$out/summary.json")"
import json, sys
m = json.load(open(sys.argv[1]))["spectrogram_maxima"]["disk.compressor.x"]
assert m["amplitude"] > 0 and m["unit"] == "m", m
assert abs(m["frequency_hz"] - 512) < 0.05 * 512, m
assert abs(m["speed_hz"] - 512) < 0.15 * 512, m
# A linear rotor on linear bearings does not whirl below its speed: what the sub-synchronous measure finds is the
# passage's ringing and the resonance's leakage, below 1e-3 of the resonance.
for key in ("subsynchronous", "subsynchronous_at_end"):
    s = m[key]
    assert 0 < s["amplitude"] < 1e-3 * m["amplitude"], (key, m)
    assert 0 < s["order"] < 1 and abs(s["frequency_hz"] / s["speed_hz"] - s["order"]) < 1e-12, (key, m)
EOF2
    ;;
  plot_redraws)
    # turbodyn plot redraws a run's pictures from its timeseries.h5: the same pictures and spectral maxima.
    "$exe" run "$src/examples/reference_linear.toml" --set "speed.end=40000 rpm" --set speed.duration=0.5 \
      -o "$out/run" > "$out/log" 2>&1 || fail "run: exit $?: $(cat "$out/log")"
    cp "$out/run/summary.json" "$out/summary.orig.json"
    rm "$out/run/"*.png
    "$exe" plot "$out/run" > "$out/log" 2>&1 || fail "plot: exit $?: $(cat "$out/log")"
    [ -s "$out/run/spectrogram_disk.compressor.x.png" ] || fail "no spectrogram redrawn"
    python3 - "$out/summary.orig.json" "$out/run/summary.json" <<'EOF2' || fail "redrawn summary differs"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert a["pictures"] == b["pictures"] and a["spectrogram_maxima"] == b["spectrogram_maxima"]
EOF2
    # A run without pictures measures the same maxima and sub-synchronous lines.
    "$exe" run "$src/examples/reference_linear.toml" --set "speed.end=40000 rpm" --set speed.duration=0.5 --no-plots \
      -o "$out/np" > "$out/log" 2>&1 || fail "run --no-plots: exit $?: $(cat "$out/log")"
    grep -q "largest sub-synchronous line at the end, disk.compressor.x" "$out/log" ||
      fail "run --no-plots: no sub-synchronous line in the output: $(cat "$out/log")"
    ! ls "$out/np/"*.png > /dev/null 2>&1 || fail "run --no-plots drew pictures"
    python3 - "$out/summary.orig.json" "$out/np/summary.json" <<'EOF2' || fail "maxima without pictures differ"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert b["pictures"] == [] and a["spectrogram_maxima"] == b["spectrogram_maxima"], b["spectrogram_maxima"]
EOF2
    # With the natural frequencies of the linear model drawn on the spectrograms; a foreign file is refused.
    "$exe" modal "$src/examples/reference_linear.toml" --no-plots -o "$out/modal" > "$out/log" 2>&1 || fail "modal"
    "$exe" plot "$out/run" --campbell "$out/modal/campbell.csv" > "$out/log" 2>&1 || fail "plot --campbell: $(cat "$out/log")"
    "$exe" plot "$out/run" --campbell "$out/run/summary.json" > "$out/log" 2>&1
    [ $? -eq 2 ] && grep -q "not a campbell.csv" "$out/log" || fail "bad --campbell file: $(cat "$out/log")"
    # The critical speeds at an amplitude of `turbodyn modal --amplitudes` on the compressor wheel's 1x order track.
    "$exe" modal "$src/examples/reference_linear.toml" --amplitudes "1, 10 um" --no-plots -o "$out/backbone" \
      > "$out/log" 2>&1 || fail "modal --amplitudes: $(cat "$out/log")"
    rm "$out/run/order1x_disk.compressor.png"
    "$exe" plot "$out/run" --backbone "$out/backbone/modal.json" > "$out/log" 2>&1 || fail "plot --backbone: $(cat "$out/log")"
    [ -s "$out/run/order1x_disk.compressor.png" ] || fail "no order track redrawn"
    grep -q '"warnings": \[\]' "$out/run/summary.json" || fail "warnings: $(grep -A3 warnings "$out/run/summary.json")"
    expect_plot_error() {  # expected-message then arguments
      local msg=$1; shift
      "$exe" plot "$out/run" "$@" > "$out/log" 2>&1
      local rc=$?
      [ $rc -eq 2 ] && grep -q -- "$msg" "$out/log" || fail "exit $rc for $*: $(cat "$out/log")"
    }
    expect_plot_error "not a modal.json" --backbone "$out/modal/campbell.csv"
    expect_plot_error "not a modal.json of turbodyn modal --amplitudes" --backbone "$out/modal/modal.json"
    "$exe" modal "$src/examples/reference_linear.toml" --amplitudes "1 um" --amplitude-at bearings.turbine --no-plots \
      -o "$out/backbone_bearing" > "$out/log" 2>&1 || fail "modal --amplitude-at bearings.turbine: $(cat "$out/log")"
    expect_plot_error "order tracks of the disks' displacements only" --backbone "$out/backbone_bearing/modal.json"
    # The steady states of `turbodyn response --nonlinear` (here the linear rotor's: the same curve) on the order tracks.
    "$exe" response "$src/examples/reference_linear.toml" --speeds "5000:40000 rpm:8" --nonlinear --no-plots \
      -o "$out/response" > "$out/log" 2>&1 || fail "response --nonlinear: $(cat "$out/log")"
    rm "$out/run/order1x_disk.compressor.png"
    "$exe" plot "$out/run" --response "$out/response/response.json" > "$out/log" 2>&1 \
      || fail "plot --response: $(cat "$out/log")"
    [ -s "$out/run/order1x_disk.compressor.png" ] || fail "no order track redrawn with --response"
    grep -q '"warnings": \[\]' "$out/run/summary.json" || fail "warnings: $(grep -A3 warnings "$out/run/summary.json")"
    expect_plot_error "not a response.json of turbodyn response --nonlinear" --response "$out/modal/modal.json"
    "$exe" plot "$out/nowhere" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "plot of a missing directory: exit $rc, expected 2"
    grep -q "nowhere/summary.json" "$out/log" || fail "the message does not name the file: $(cat "$out/log")"
    ;;
  run_film_limit)
    # A journal bearing whose film gets thinner than the model file's permissible minimum: the run warns (naming the
    # probe, where it is first passed, the smallest film and what the limit means), marks it in summary.json, draws
    # the film-thickness picture, and `turbodyn plot` warns again. The other bearing has no limit: no warning.
    "$exe" run "$src/examples/reference_journal.toml" --set "speed.end=15000 rpm" --set speed.duration=0.4 \
      --set bearings.turbine.film_thickness_limit=5um -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    said="warning: bearing.turbine.min_film_thickness is first below its limit of 5.0 µm at .* rpm (t = .* s),"
    said+=" smallest .* µm at .* rpm. The limit: the permissible minimum film thickness of the model file"
    grep -q "$said (film_thickness_limit)" "$out/log" || fail "no film warning: $(cat "$out/log")"
    grep -q "warning: bearing.compressor" "$out/log" && fail "a warning without a limit: $(cat "$out/log")"
    expect_files "$out" film_thickness.png
    [ -e "$out/spectrogram_bearing.turbine.min_film_thickness.png" ] && fail "a spectrogram of a film thickness"
    python3 - "$out/summary.json" <<'EOF2' || fail "summary: $(grep -A12 min_film_thickness "$out/summary.json")"
import json, sys
p = json.load(open(sys.argv[1]))["probes"]
t, c = p["bearing.turbine.min_film_thickness"], p["bearing.compressor.min_film_thickness"]
assert t["limit"] == 5e-6 and t["limit_below"] is True and t["over_limit"]["speed_rpm"] > 0, t
assert t["min"] < 5e-6 and t["unit"] == "m", t
assert "limit" not in c and 0 < c["min"] < 15e-6, c
EOF2
    "$exe" plot "$out" > "$out/log" 2>&1 || fail "plot: $(cat "$out/log")"
    grep -q "warning: bearing.turbine.min_film_thickness is first below its limit" "$out/log" ||
      fail "plot does not warn: $(cat "$out/log")"
    ;;
  run_integrator_gives_up)
    # BDF takes few steps per output interval at low speed and more at high speed: a step limit of 30 per
    # 0.5 ms interval makes it give up part-way through the run.
    "$exe" run "$src/examples/reference_linear.toml" --set solver.integrator=cvode-bdf --set solver.max_steps=30 \
      --set "output.sample_rate=2 kHz" --set output.csv=true -o "$out" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 3 ] || fail "exit $rc, expected 3: $(cat "$out/log")"
    grep -q '"complete": false' "$out/summary.json" || fail "summary not marked incomplete"
    grep -q "stopped at t = " "$out/log" || fail "no time in the message: $(cat "$out/log")"
    grep -q "TOO_MUCH_WORK" "$out/log" || fail "no cause in the message"
    [ -s "$out/timeseries.h5" ] && [ -s "$out/timeseries.csv" ] || fail "partial results not written"
    [ "$(wc -l < "$out/timeseries.csv")" -gt 2 ] || fail "no rows in the partial CSV"
    ;;
  run_interrupted)
    # Ctrl-C (SIGINT) ends a long run with everything so far written and marked incomplete, exit code 130.
    "$exe" run "$src/examples/reference_linear.toml" --set speed.duration=400 --no-plots -o "$out" > "$out/log" 2>&1 &
    sleep 2
    stop INT $!
    [ $rc -eq 130 ] || fail "exit $rc, expected 130: $(cat "$out/log")"
    grep -q '"complete": false' "$out/summary.json" || fail "summary not marked incomplete"
    grep -q "interrupted" "$out/log" || fail "no reason given: $(cat "$out/log")"
    [ -s "$out/timeseries.h5" ] || fail "partial results not written"
    ;;
  run_interrupted_between_samples)
    # Issue 20: Ctrl-C was checked only between output samples, so a run that took no sample for minutes ignored it.
    # One sample a minute of simulated time here: SIGINT and SIGTERM end the run within a second anyway.
    for sig in INT TERM; do
      "$exe" run "$src/examples/reference_linear.toml" --set speed.duration=400 --set "output.sample_rate=0.02 Hz" \
        --no-plots -o "$out/$sig" > "$out/$sig.log" 2>&1 &
      pid=$!
      sleep 2
      kill -$sig $pid
      start=$(date +%s%N)
      wait $pid
      rc=$?
      ms=$((($(date +%s%N) - start) / 1000000))
      [ $rc -eq 130 ] || fail "SIG$sig: exit $rc, expected 130: $(cat "$out/$sig.log")"
      echo "SIG$sig: stopped after $ms ms"
      # The aim is well under a second; the bound is loose so that a loaded machine does not fail it (before, the
      # run went on for minutes).
      [ $ms -lt 5000 ] || fail "SIG$sig: the run took $ms ms to stop"
      grep -q "interrupted" "$out/$sig.log" || fail "SIG$sig: no reason given: $(cat "$out/$sig.log")"
      grep -q '"complete": false' "$out/$sig/summary.json" || fail "SIG$sig: summary not marked incomplete"
    done
    ;;
  run_killed_keeps_its_samples)
    # Issue 20: SIGKILL kept only whole 4,096-row blocks of the time series and no summary.json, and `turbodyn plot`
    # refused the directory. Now the samples are flushed each second and the summary is written at the start.
    "$exe" run "$src/examples/reference_linear.toml" --set speed.duration=400 --no-plots -o "$out" > "$out/log" 2>&1 &
    sleep 4
    stop KILL $! 2>/dev/null
    grep -q '"complete": false' "$out/summary.json" || fail "no summary marked incomplete: $(cat "$out/summary.json")"
    "$exe" plot "$out" > "$out/plot.log" 2>&1 || fail "plot refused the killed run: $(cat "$out/plot.log")"
    grep -q "(the run is incomplete)" "$out/plot.log" || fail "plot: $(cat "$out/plot.log")"
    ls "$out"/*.png > /dev/null 2>&1 || fail "no pictures from the killed run's samples"
    ;;
  sweep_kill_and_resume)
    # A study killed hard (SIGKILL) part-way resumes where it stopped, without redoing finished runs.
    study="$src/examples/study_reference_linear.toml"
    "$exe" sweep "$study" -o "$out" -j 1 --no-plots > "$out/log1" 2>&1 &
    wait_until has_lines "$out/runs.jsonl" 4
    stop KILL $! 2>/dev/null
    done_before=$(($(wc -l < "$out/runs.jsonl") - 1))
    [ "$done_before" -ge 3 ] && [ "$done_before" -lt 16 ] || fail "expected a partial study, found $done_before runs"
    "$exe" sweep "$study" -o "$out" --no-plots > "$out/log2" 2>&1 || fail "resume failed: $(cat "$out/log2")"
    grep -q "16 of 16 runs recorded ($done_before resumed" "$out/log2" || fail "not resumed: $(cat "$out/log2")"
    [ "$(wc -l < "$out/runs.jsonl")" -eq 17 ] || fail "runs were redone or lost: $(wc -l < "$out/runs.jsonl") lines"
    [ "$(wc -l < "$out/results.csv")" -eq 17 ] || fail "results table incomplete"
    ;;
  sweep_shards_merge)
    study="$src/examples/study_reference_linear.toml"
    for k in 0 1 2; do
      "$exe" sweep "$study" --shard $k/3 -o "$out/shard_$k" --no-plots > "$out/log_$k" 2>&1 || fail "shard $k: $(cat "$out/log_$k")"
    done
    "$exe" merge "$study" "$out"/shard_* -o "$out/merged" --no-plots > "$out/log_merge" 2>&1 || fail "merge: $(cat "$out/log_merge")"
    grep -q "merged 16 of 16 runs" "$out/log_merge" || fail "merge: $(cat "$out/log_merge")"
    [ "$(wc -l < "$out/merged/results.csv")" -eq 17 ] || fail "merged table incomplete"
    "$exe" sweep "$study" --shard 3/3 -o "$out/bad" > "$out/log_bad" 2>&1
    [ $? -eq 2 ] || fail "--shard 3/3 accepted"
    ;;
  journal_raimondi_boyd)
    # Raimondi & Boyd (1958), L/D = 1, eps = 0.6: S = 0.121, (R/c) f = 3.22 (docs/references.md §1), 3 %.
    "$exe" journal --ld 1 --eccentricity 0.6 --viscosity "10 mPa*s" --speed "3000 rpm" > "$out/j.json" 2>&1 \
      || fail "exit $?: $(cat "$out/j.json")"
    get() { grep "\"$1\"" "$out/j.json" | head -1 | sed 's/.*: *//; s/,$//'; }
    awk -v s="$(get sommerfeld_number)" -v f="$(get friction_variable)" \
      'BEGIN { exit !(s > 0.121 * 0.97 && s < 0.121 * 1.03 && f > 3.22 * 0.97 && f < 3.22 * 1.03) }' \
      || fail "S = $(get sommerfeld_number), (R/c)f = $(get friction_variable)"
    # The thinnest film, h0 = c (1 - e/c) of the parallel journal (Raimondi & Boyd's h0/c = 0.4 here).
    awk -v h="$(get min_film_thickness_m)" -v c="$(get clearance_m)" \
      'BEGIN { exit !(c > 0 && h > 0.4 * c * (1 - 1e-12) && h < 0.4 * c * (1 + 1e-12)) }' \
      || fail "h_min = $(get min_film_thickness_m) m for c = $(get clearance_m) m"
    "$exe" journal --eccentricity 1.2 > "$out/bad.log" 2>&1
    [ $? -eq 2 ] || fail "eccentricity 1.2 accepted"
    ;;
  journal_groove)
    # A central feed groove, deep against the clearance, carries no shear: the centred journal's torque is
    # Petroff's over the two lands, (L - w) / L of the plain bearing's (D = L = 10 mm, w = 2 mm: 0.8).
    "$exe" journal --ld 1 --eccentricity 0 --viscosity "10 mPa*s" --speed "30000 rpm" > "$out/plain.json" 2>&1 \
      || fail "exit $?: $(cat "$out/plain.json")"
    "$exe" journal --ld 1 --eccentricity 0 --viscosity "10 mPa*s" --speed "30000 rpm" --groove-width "2 mm" \
      --supply-pressure "2 bar" > "$out/groove.json" 2>&1 || fail "exit $?: $(cat "$out/groove.json")"
    get() { grep "\"$2\"" "$out/$1.json" | head -1 | sed 's/.*: *//; s/,$//'; }
    awk -v a="$(get groove torque_on_journal_n_m)" -v b="$(get plain torque_on_journal_n_m)" \
      'BEGIN { r = a / b; exit !(r > 0.8 - 1e-9 && r < 0.8 + 1e-9) }' \
      || fail "torques $(get groove torque_on_journal_n_m) and $(get plain torque_on_journal_n_m) N m"
    grep -q '"groove_width_m": 0.002' "$out/groove.json" || fail "input: $(head -c 800 "$out/groove.json")"
    # The supply leaves at both ends.
    awk -v q="$(get groove flow_out_of_ends_m3_s)" 'BEGIN { exit !(q > 0) }' \
      || fail "no flow: $(cat "$out/groove.json")"
    # Refused: hole and groove together, a groove as wide as the bearing, a supply with no way in.
    refused() {  # refused PATTERN ARGS...
      local pattern=$1
      shift
      "$exe" journal --ld 1 "$@" > "$out/bad.log" 2>&1
      local rc=$?
      [ $rc -eq 2 ] && grep -q -- "$pattern" "$out/bad.log" || fail "$*: exit $rc: $(cat "$out/bad.log")"
    }
    refused "not both" --groove-width "2 mm" --hole-diameter "2 mm"
    refused "groove-width: must lie" --groove-width "10 mm"
    refused "supply-pressure: needs a feed hole" --supply-pressure "2 bar"
    refused "groove-width 0.5 mm --n-axial 12: the groove (0.5 mm wide" --groove-width "0.5 mm"
    refused "the groove (9.9 mm wide at z = 0 mm) leaves no land" --groove-width "9.9 mm"
    ;;
  bearing_reference_ball)
    # turbodyn bearing on the reference ball bearing: files, the picture, a radial stiffness at rest of about
    # 4.96e7 N/m (the element's static value) and a cage speed ratio that rises with speed.
    "$exe" bearing "$src/examples/reference_ball.toml" --bearing turbine --speeds "0:100000 rpm:5" --load "20,-10" \
      -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" bearing.json bearing.csv bearing_balls.csv stiffness.png tilt_stiffness.png
    python3 - "$out/bearing.json" <<'EOF2' || fail "bearing.json: $(head -c 2000 "$out/bearing.json")"
import json, sys
j = json.load(open(sys.argv[1]))
r = j["results"]
assert j["bearing"]["name"] == "turbine" and len(r) == 5, (j["bearing"], len(r))
assert abs(r[0]["force_on_inner_ring"][0] + 20) < 1e-6 and abs(r[0]["force_on_inner_ring"][1] - 10) < 1e-6
assert 4.5e7 < r[0]["stiffness"][0][0] < 5.5e7, r[0]["stiffness"][0][0]
assert r[-1]["cage_speed_ratio"] > r[1]["cage_speed_ratio"] > 0.3
assert len(r[-1]["balls"]) == 8
assert j["bearing"]["hertz_law"] == "ellipse" and j["bearing"]["hertz_coefficient"] == 0
# Hertz pressures: each speed's largest is its balls' largest; about 1,000 MPa under the 40 N preload at rest (17-19 N
# per ball, docs/ball-bearing.md), far below ISO 76's 4,200 MPa, so no warning.
for p in r:
    assert p["max_contact_pressure_pa"] == max(max(b["inner_pressure_pa"], b["outer_pressure_pa"]) for b in p["balls"])
assert 0.9e9 < r[0]["max_contact_pressure_pa"] < 1.3e9, r[0]["max_contact_pressure_pa"]
assert j["static_contact_pressure_limit_pa"] == 4.2e9 and j["warnings"] == [], j["warnings"]
EOF2
    head -1 "$out/bearing_balls.csv" | grep -q ",inner_pressure_pa,outer_pressure_pa$" \
      || fail "bearing_balls.csv: $(head -1 "$out/bearing_balls.csv")"
    # 8,000 N of thrust at rest puts about 1,700 N on each ball, above ISO 76's static limit: a warning on
    # standard error and in bearing.json, the results still written (exit 0).
    "$exe" bearing "$src/examples/reference_ball.toml" --speeds "0 rpm" --load "0,0,8000" --no-plots -o "$out/heavy" \
      > "$out/heavy.log" 2>&1 || fail "exit $?: $(cat "$out/heavy.log")"
    grep -q "warning: at 0 rpm the largest contact pressure is .* MPa, above its limit of 4200 MPa, ISO 76's static" \
      "$out/heavy.log" || fail "no pressure warning: $(cat "$out/heavy.log")"
    python3 - "$out/heavy/bearing.json" <<'EOF2' || fail "heavy: $(head -c 2000 "$out/heavy/bearing.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["results"][0]["max_contact_pressure_pa"] > 4.2e9 and len(j["warnings"]) == 1, j["warnings"]
EOF2
    # The paper's Eq. 20 (mu* 0.171): stiffer contacts, about 4x the radial stiffness at rest (docs/ball-bearing.md).
    "$exe" bearing "$src/examples/reference_ball.toml" --bearing turbine --speeds "0 rpm" --load "20,-10" --no-plots \
      --set bearings.turbine.hertz_law=paper -o "$out/paper" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    python3 - "$out/bearing.json" "$out/paper/bearing.json" <<'EOF2' || fail "paper: $(head -c 2000 "$out/paper/bearing.json")"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert b["bearing"]["hertz_law"] == "paper" and b["bearing"]["hertz_coefficient"] == 0.171, b["bearing"]
ratio = b["bearing"]["inner_hertz_constant_n_per_m1_5"] / a["bearing"]["inner_hertz_constant_n_per_m1_5"]
assert 6.4 < ratio < 6.6, ratio
k = b["results"][0]["stiffness"][0][0] / a["results"][0]["stiffness"][0][0]
assert 3.5 < k < 4.5, k
EOF2
    # The load-deflection curve (--radial-travel): one per speed in the JSON, the CSV and the picture; the bare
    # START takes END's unit; the load rises with the travel and the secant stiffness hardens (Hertz).
    "$exe" bearing "$src/examples/reference_ball.toml" --speeds "0, 46000 rpm" --radial-travel "0:50 um:6" \
      -o "$out/ld" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out/ld" load_deflection.csv load_deflection.png
    [ "$(wc -l < "$out/ld/load_deflection.csv")" -eq 13 ] || fail "load_deflection.csv: $(cat "$out/ld/load_deflection.csv")"
    python3 - "$out/ld/bearing.json" <<'EOF2' || fail "load_deflection: $(head -c 3000 "$out/ld/bearing.json")"
import json, sys
c = json.load(open(sys.argv[1]))["load_deflection"]["curves"]
assert len(c) == 2 and c[1]["speed_rpm"] == 46000 and len(c[1]["points"]) == 6
p = c[1]["points"]
assert abs(p[-1]["travel_m"] - 50e-6) < 1e-12
assert all(b["load_n"] > a["load_n"] for a, b in zip(p, p[1:]))
assert p[-1]["secant_stiffness_n_per_m"] > 3 * p[0]["tangent_stiffness_n_per_m"]
# The contact pressure: p0 = c Q^(1/3), Hertz's, c between the outer and the inner contact's 334 and 386 MPa/N^(1/3)
# (the centrifugal force loads the outer contacts most at small travel); at rest the preload's 17.4 N give 1,000 MPa
# (docs/ball-bearing.md); at 50 um the curve passes ISO 76's 4,200 MPa, which is warned of.
p0 = c[0]["points"]
assert abs(p0[0]["max_contact_pressure_pa"] / 1e9 - 1.0) < 0.01, p0[0]
for a in p0 + p:
    assert 3.3e8 < a["max_contact_pressure_pa"] / a["max_contact_load_n"] ** (1 / 3) < 3.9e8, a
assert p[-1]["max_contact_pressure_pa"] > 4.2e9 and p[-2]["max_contact_pressure_pa"] < 4.2e9, p
EOF2
    grep -q "warning: the load-deflection curve at 46000 rpm passes the contact pressure's limit of 4200 MPa at 50.00 um" \
      "$out/log" || fail "no pressure warning: $(cat "$out/log")"
    head -1 "$out/ld/load_deflection.csv" | grep -q "max_contact_load_n,max_contact_pressure_pa$" \
      || fail "csv: $(head -1 "$out/ld/load_deflection.csv")"
    ;;
  bearing_floating_ring)
    # turbodyn bearing on the reference floating ring with thermal films: files, pictures, the ring speed ratio
    # falling with speed below the isothermal Petroff value, the inner film hotter than the outer one.
    "$exe" bearing "$src/examples/reference_floating_ring.toml" --bearing compressor --speeds "20000 rpm:150000 rpm:4" \
      --load "0,-1.6" --set bearings.compressor.thermal=bulk -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" bearing.json bearing.csv ring_speed_ratio.png eccentricity.png temperatures.png power_loss.png
    python3 - "$out/bearing.json" <<'EOF2' || fail "bearing.json: $(head -c 2000 "$out/bearing.json")"
import json, sys
j = json.load(open(sys.argv[1]))
r = j["results"]
assert j["bearing"]["thermal"] == "bulk" and len(r) == 4, (j["bearing"], len(r))
assert 0.2 < r[-1]["ring_speed_ratio"] < r[1]["ring_speed_ratio"] < 0.3131, [p["ring_speed_ratio"] for p in r]
assert all(p["inner_temperature_k"] > p["outer_temperature_k"] > 363.15 for p in r)
assert abs(r[-1]["inner_power_w"] + r[-1]["outer_power_w"] - r[-1]["heat_to_oil_w"] - r[-1]["heat_conducted_w"]) < 1e-3
# Each film's thinnest point, journal and ring aligned: c (1 - e/c); no limit in the model file, no warning.
b = j["bearing"]
for p in r:
    assert abs(p["inner_min_film_thickness_m"] - b["inner_clearance_m"] * (1 - p["inner_eccentricity"])) < 1e-15, p
    assert abs(p["outer_min_film_thickness_m"] - b["outer_clearance_m"] * (1 - p["outer_eccentricity"])) < 1e-15, p
assert j["warnings"] == [] and "film_thickness_limit_m" not in b, j["warnings"]
# The drill holes feed the inner film below the supply pressure (4.5 bar through the top hole)
holes = [p["drill_hole_pressure_pa"] for p in r]
assert all(0 <= h < b["supply_pressure_pa"] for h in holes), holes
EOF2
    # Fed through a groove instead of the hole, every drill hole sees the supply pressure less the centrifugal head
    # of the oil column turning with the ring, rho w_r^2 (R_o^2 - R_i^2) / 2 (none once the head passes the supply).
    "$exe" bearing "$src/examples/reference_floating_ring.toml" --bearing turbine --speeds "20000 rpm:150000 rpm:3" \
      --set bearings.turbine.feed_hole_diameter=0mm --set "bearings.turbine.feed_groove_width=2 mm" --no-plots \
      -o "$out/groove" > "$out/groove.log" 2>&1 || fail "groove: exit $?: $(cat "$out/groove.log")"
    python3 - "$out/groove/bearing.json" <<'EOF2' || fail "groove: $(head -c 2000 "$out/groove/bearing.json")"
import json, sys
j = json.load(open(sys.argv[1]))
b = j["bearing"]
assert b["feed_groove_width_m"] == 0.002 and b["feed_hole_diameter_m"] == 0, b
for p in j["results"]:
    ro, ri = b["outer_diameter_m"] / 2, b["inner_diameter_m"] / 2
    head = 0.5 * 850 * p["ring_speed_rad_s"] ** 2 * (ro ** 2 - ri ** 2)
    expected = max(b["supply_pressure_pa"] - head, 0.0)
    assert abs(p["drill_hole_pressure_pa"] - expected) < 1e-6 * b["supply_pressure_pa"], (p["speed_rpm"], expected, p)
    assert p["outer_eccentricity"] < 0.02, p  # the groove's pressure is the same all round: no push on the ring
assert j["results"][-1]["drill_hole_pressure_pa"] == 0.0  # 150,000 rpm: the head passes the 4.5 bar
EOF2
    # 40 N on the journal and a permissible minimum film thickness of 12 µm: at 20,000 rpm the ring sits low in its
    # outer film (about 9 µm left), at 150,000 rpm both films are thicker (about 14 and 30 µm). One warning, on
    # standard error and in bearing.json; the results written, exit 0.
    "$exe" bearing "$src/examples/reference_floating_ring.toml" --bearing compressor --speeds "20000 rpm:150000 rpm:2" \
      --load "0,-40" --set bearings.compressor.film_thickness_limit=12um --no-plots -o "$out/limit" \
      > "$out/limit.log" 2>&1 || fail "exit $?: $(cat "$out/limit.log")"
    grep -q "warning: at 20000 rpm the outer film is .* µm thin, below its limit of 12.00 µm, the permissible" \
      "$out/limit.log" || fail "no film warning: $(cat "$out/limit.log")"
    python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert len(j['warnings']) == 1, j['warnings']" \
      "$out/limit/bearing.json" || fail "warnings in bearing.json"
    ;;
  modal_floating_ring)
    # turbodyn modal on variant I: the films linearised at steady points under the rotor's weight, ring masses as
    # coordinates of their own; the films' forward whirl modes have negative damping ratios (the whirl the run-up
    # shows), and damping.png is drawn. A bare START takes END's unit (the form of the option's help).
    "$exe" modal "$src/examples/reference_floating_ring.toml" --speeds "30000:150000 rpm:3" -o "$out" \
      > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" modal.json campbell.csv campbell.png damping.png
    python3 - "$out/modal.json" <<'EOF2' || fail "modal.json: $(head -c 2000 "$out/modal.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert [round(p["speed_rpm"]) for p in j["campbell"]] == [30000, 90000, 150000], [p["speed_rpm"] for p in j["campbell"]]
for p in j["campbell"]:
    modes = p["modes"]
    assert any(m["whirl"] == "forward" and m["damping_ratio"] < 0 for m in modes), p
    assert any(m["damping_ratio"] > 0 for m in modes), p
EOF2
    # Between 30,000 and 35,000 rpm a heavily damped ring mode (73 Hz) turns up among the backward ones, so the
    # backward branches' order changes there: a jump of a branch across an order line is no critical speed. The one
    # backward 1x crossing is the 536-Hz mode's, whose branch falls (s = -0.11), and its AF is first order's.
    "$exe" modal "$src/examples/reference_floating_ring.toml" --speeds "25000:40000 rpm:4" --no-plots \
      -o "$out/jump" > "$out/jump.log" 2>&1 || fail "exit $?: $(cat "$out/jump.log")"
    python3 - "$out/jump/modal.json" <<'EOF2' || fail "critical speeds: $(cat "$out/jump.log")"
import json, sys
crit = json.load(open(sys.argv[1]))["critical_speeds"]
assert len(crit) == 2, crit
back = [c for c in crit if c["whirl"] == "backward"]
assert len(back) == 1 and back[0]["order"] == 1.0 and 530 < back[0]["frequency_hz"] < 540, back
c = back[0]
assert -0.13 < c["branch_slope"] < -0.09 and not c["critically_damped"], c
assert abs(c["amplification_factor"] - (1 - c["branch_slope"]) / (2 * c["damping_ratio"])) < 1e-9 * c["amplification_factor"]
EOF2
    ;;
  bearing_bad_input)
    # Each bad input: exit 2 and a message naming the file or option and the cause.
    expect_error() {  # expected-message then arguments
      local msg=$1; shift
      "$exe" bearing "$@" -o "$out" > "$out/log" 2>&1
      local rc=$?
      [ $rc -eq 2 ] || fail "exit $rc for $*: $(cat "$out/log")"
      grep -q -- "$msg" "$out/log" || fail "message for $*: $(cat "$out/log")"
    }
    expect_error "bearings.nope: no such bearing\|--bearing 'nope': no such bearing" \
      "$src/examples/reference_ball.toml" --bearing nope --speeds 0
    expect_error "bearings.compressor is a linear bearing" "$src/examples/reference_linear.toml" --bearing compressor --speeds 0
    expect_error "the model has no ball or floating-ring bearing" "$src/examples/reference_linear.toml" --speeds 0
    expect_error "needs speeds above 0" "$src/examples/reference_floating_ring.toml" --speeds 0
    expect_error "takes no axial load" "$src/examples/reference_floating_ring.toml" --speeds "30000 rpm" --load "0,-2,5"
    expect_error "bearings.compressor.ring_conductance: must not be negative" \
      "$src/examples/reference_floating_ring.toml" --speeds "30000 rpm" --set bearings.compressor.thermal=bulk \
      --set "bearings.compressor.ring_conductance=-2 W/K"
    expect_error "--speeds '0:1:x'" "$src/examples/reference_ball.toml" --speeds 0:1:x
    expect_error "--load '1;2'" "$src/examples/reference_ball.toml" --speeds 0 --load "1;2"
    expect_error "--load '1,2,3,4'" "$src/examples/reference_ball.toml" --speeds 0 --load "1,2,3,4"
    expect_error "--load '1 kg,2'" "$src/examples/reference_ball.toml" --speeds 0 --load "1 kg,2"
    expect_error "cannot carry the load" "$src/examples/reference_ball.toml" --speeds 0 --load "3e6,0"
    expect_error "--radial-travel '5:1 um:3': END must be larger than START" "$src/examples/reference_ball.toml" \
      --speeds 0 --radial-travel "5:1 um:3"
    expect_error "--radial-travel '5 um, 1 um': travels must be increasing" "$src/examples/reference_ball.toml" \
      --speeds 0 --radial-travel "5 um, 1 um"
    expect_error "expected a length" "$src/examples/reference_ball.toml" --speeds 0 --radial-travel "1 N"
    expect_error "give one of them" "$src/examples/reference_ball.toml" --speeds 0 --radial-travel "1 um" --load "1,0"
    expect_error "cannot be moved by" "$src/examples/reference_ball.toml" --speeds 0 --radial-travel "1 mm"
    expect_error "are for ball bearings" "$src/examples/reference_floating_ring.toml" --speeds "30000 rpm" \
      --radial-travel "1 um"
    expect_error "pitch_diameter" "$src/examples/reference_ball.toml" --speeds 0 \
      --set "bearings.compressor.pitch_diameter=4 mm"
    ;;
  modal_reference_ball)
    # turbodyn modal linearises the ball bearings at every speed; a damper is refused as nonlinear.
    "$exe" modal "$src/examples/reference_ball.toml" --speeds "0:150000 rpm:7" --no-plots -o "$out" > "$out/log" 2>&1 \
      || fail "exit $?: $(cat "$out/log")"
    grep -q "1x  forward branch 1" "$out/log" || fail "no critical speeds: $(cat "$out/log")"
    "$exe" modal "$src/examples/reference_ball_sfd.toml" --speeds "0:150000 rpm:7" -o "$out/sfd" > "$out/sfd.log" 2>&1
    [ $? -eq 2 ] || fail "damper accepted: $(cat "$out/sfd.log")"
    grep -q "squeeze-film dampers are nonlinear" "$out/sfd.log" || fail "message: $(cat "$out/sfd.log")"
    # turbodyn response takes the same linearisation; floating rings stay refused there.
    "$exe" response "$src/examples/reference_ball.toml" --speeds "20000:50000 rpm:31" -o "$out/response" \
      > "$out/response.log" 2>&1 || fail "response: exit $?: $(cat "$out/response.log")"
    expect_files "$out/response" response.csv response.json response.png
    head -1 "$out/response/response.csv" | grep -q "bearing.compressor.fx_amplitude_n" || fail "no bearing forces"
    "$exe" response "$src/examples/reference_floating_ring.toml" -o "$out/fr" > "$out/fr.log" 2>&1
    [ $? -eq 2 ] && grep -q "floating-ring bearings are in the linear analyses of .turbodyn modal. only" "$out/fr.log" \
      || fail "floating rings in response: $(cat "$out/fr.log")"
    ;;
  modal_amplitudes)
    # turbodyn modal --amplitudes: the forward 1x critical speeds at a whirl amplitude (model/engine/backbone.h).
    # Variant II's second critical hardens from 700 Hz towards the run's passage (docs/validation.md); outputs and
    # bad input.
    "$exe" modal "$src/examples/reference_ball.toml" --speeds "36000:60000 rpm:9" --amplitudes "100, 500 um" \
      -o "$out" > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" modal.json backbone.csv backbone.png report.html
    grep -q "^ *500.000 um: *4561[0-9] rpm (760.[0-9] Hz)" "$out/log" || fail "branch 2 at 500 um: $(cat "$out/log")"
    head -1 "$out/backbone.csv" | grep -q "^branch,amplitude_at,amplitude_m,speed_rad_s" || fail "csv: $(head -1 "$out/backbone.csv")"
    python3 - "$out/modal.json" <<'EOF2' || fail "modal.json backbones"
import json, sys
b = json.load(open(sys.argv[1]))["backbones"]
second = b["branches"][0]
assert second["amplitude_at"] == "disks.compressor", second["amplitude_at"]
assert second["branch"] == 1 and second["complete"] and len(second["points"]) == 2, second
assert 45000 < second["points"][1]["speed_rpm"] < 46000, second["points"][1]
# The whirl's contact loads as Hertz pressures: at 500 um the compressor bearing passes ISO 76's limit (warned of).
comp = [x for x in second["points"][1]["bearings"] if x["name"] == "compressor"][0]
assert comp["max_contact_pressure_pa"] > 4.2e9 and comp["max_contact_load_n"] > 1500, comp
EOF2
    grep -q "warning: the backbone of forward branch 2 passes the contact pressure's limit of 4200 MPa in bearings.compressor" \
      "$out/log" || fail "no pressure warning: $(cat "$out/log")"
    grep -q "<li>the backbone of forward branch 2 passes the contact pressure" "$out/report.html" \
      || fail "report without the pressure warning"
    # Without --amplitude-at each branch is measured at the wheel that moves most in its mode.
    "$exe" modal "$src/examples/reference_ball.toml" --speeds "0:60000 rpm:13" --amplitudes "10, 40 um" --no-plots \
      -o "$out/both" > "$out/both.log" 2>&1 || fail "exit $? for both branches: $(cat "$out/both.log")"
    grep -q "branch 1 (linearised: 32897 rpm), amplitude at disks.turbine" "$out/both.log" || fail "$(cat "$out/both.log")"
    grep -q "branch 2 (linearised: 42004 rpm), amplitude at disks.compressor" "$out/both.log" || fail "$(cat "$out/both.log")"
    # The first mode hardly moves the compressor wheel: its amplitude there turns back at about 30 um, where the
    # backbone ends, written so far and marked, exit 3.
    "$exe" modal "$src/examples/reference_ball.toml" --speeds "0:60000 rpm:13" --amplitudes "10, 40 um" --no-plots \
      --amplitude-at disks.compressor -o "$out/fold" > "$out/fold.log" 2>&1
    [ $? -eq 3 ] || fail "exit $? for a fold: $(cat "$out/fold.log")"
    grep -q "branch 1's critical speeds at an amplitude end early: no synchronous whirl found beyond" "$out/fold.log" \
      || fail "fold message: $(cat "$out/fold.log")"
    python3 -c "import json,sys; b=json.load(open(sys.argv[1]))['backbones']['branches']; assert not b[0]['complete'] and len(b[0]['points']) == 1" \
      "$out/fold/modal.json" || fail "fold not marked"
    grep -q "Forward 1x critical speeds at a whirl amplitude" "$out/fold/report.html" || fail "no report section"
    grep -q "INCOMPLETE: no synchronous whirl found beyond" "$out/fold/report.html" || fail "report: fold not marked"
    python3 "$src/tests/cli/check_report.py" "$out/fold" modal 10 || fail "report numbers"
    expect_modal_error() {  # expected-message then arguments
      local msg=$1; shift
      "$exe" modal "$@" --no-plots -o "$out/bad" > "$out/bad.log" 2>&1
      local rc=$?
      [ $rc -eq 2 ] || fail "exit $rc for $*: $(cat "$out/bad.log")"
      grep -q -- "$msg" "$out/bad.log" || fail "message for $*: $(cat "$out/bad.log")"
    }
    expect_modal_error "--amplitude-at 'disks.nope': no such disk or bearing (the model has disks.compressor" \
      "$src/examples/reference_ball.toml" --speeds "0:60000 rpm:7" --amplitudes "1 um" --amplitude-at disks.nope
    expect_modal_error "--amplitude-at 'disks.turbine': says where the amplitudes of --amplitudes are measured" \
      "$src/examples/reference_ball.toml" --speeds "0:60000 rpm:7" --amplitude-at disks.turbine
    expect_modal_error "--amplitudes '0:10 um:3': amplitudes must be greater than zero" \
      "$src/examples/reference_ball.toml" --speeds "0:60000 rpm:7" --amplitudes "0:10 um:3"
    expect_modal_error "--amplitudes '1 kg'" "$src/examples/reference_ball.toml" --speeds "0:60000 rpm:7" --amplitudes "1 kg"
    expect_modal_error "no forward 1x critical speed between 0 and 10000 rpm" \
      "$src/examples/reference_ball.toml" --speeds "0:10000 rpm:3" --amplitudes "1 um"
    expect_modal_error "--amplitudes: bearings.compressor: the critical speeds at an amplitude take ball and linear bearings only" \
      "$src/examples/reference_floating_ring.toml" --speeds "30000:150000 rpm:3" --amplitudes "1 um"
    ;;
  stability_reference_ball)
    # Issue 17: turbodyn stability on the ball-bearing rotor finds the growing forward whirl at 95,000 rpm and
    # none at 30,000 rpm (the bare 30000 takes the list's unit); a floating-ring model is refused naming the
    # bearing, exit 2.
    "$exe" stability "$src/examples/reference_ball.toml" --speeds "30000, 95000 rpm" -o "$out" > "$out/log" 2>&1 \
      || fail "exit $?: $(cat "$out/log")"
    for f in stability.json stability.csv stability_frequencies.png stability_damping.png report.html; do
      [ -s "$out/$f" ] || fail "no $f: $(cat "$out/log")"
    done
    grep -q "^ *95000 .*UNSTABLE" "$out/log" || fail "no growing mode at 95,000 rpm: $(cat "$out/log")"
    # ... and names it: the ball set's one-lobed density wave (ball-set share, lobes 1), in the listing and the CSV.
    grep -q "^ *95000 .* 0\.9[0-9]* *1   UNSTABLE" "$out/log" || fail "growing mode not a one-lobed ball-set wave: $(cat "$out/log")"
    head -1 "$out/stability.csv" | grep -q ",ball_set_share,ball_set_lobes" || fail "csv header: $(head -1 "$out/stability.csv")"
    ! grep -q "^ *30000 .*UNSTABLE" "$out/log" || fail "a growing rotor mode at 30,000 rpm: $(cat "$out/log")"
    # The report tells the growing rotor modes (95,000 rpm) from a ball set's own mode (30,000 rpm, rotor share
    # 3e-4): one speed each.
    grep -q "UNSTABLE: at 1 of the speeds analysed a mode with at least" "$out/report.html" \
      || fail "report: rotor modes: $(grep -o 'UNSTABLE[^<]*' "$out/report.html")"
    grep -q "At 1 of the speeds analysed a mode of the elements" "$out/report.html" || fail "report: elements only"
    # The onset between the two speeds, halved six times (about 54,000 rpm: docs/ball-bearing.md), in the listing,
    # the JSON and the report.
    onset=$(sed -n 's/^Onset of instability: \([0-9]*\) rpm (the speed before it halved 6 times.*/\1/p' "$out/log")
    [ -n "$onset" ] && [ "$onset" -gt 50000 ] && [ "$onset" -lt 60000 ] || fail "onset '$onset': $(cat "$out/log")"
    python3 -c "import json,sys; o=json.load(open(sys.argv[1]))['onset']; assert abs(o['speed_rpm']-$onset)<1 and \
abs(o['resolution_rpm']-65000/64)<1e-6 and o['halvings'] == 6 and 'halving_restarted_rpm' not in o, o" \
      "$out/stability.json" || fail "stability.json onset"
    grep -q "Onset of instability (a mode with at least.*halved 6 times)" "$out/report.html" || fail "report: onset"
    # Each speed continued from the one before, none restarted from rest (no fold on the example's rolling state).
    python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['results']; assert len(r) == 2 and \
not any(p['steady_state_restarted'] for p in r), r" "$out/stability.json" || fail "stability.json restarted"
    ! grep -q "^Note: at" "$out/log" || fail "a restart noted: $(cat "$out/log")"
    # Half the continuation's steps find the same steady state at 95,000 rpm (cage speed to 1e-6); a factor outside
    # (0, 1] is refused.
    "$exe" stability "$src/examples/reference_ball.toml" --speeds "95000 rpm" --continuation-steps 0.5 --no-plots \
      -o "$out/half" > "$out/half.log" 2>&1 || fail "half steps: exit $?: $(cat "$out/half.log")"
    python3 -c "import json,sys; a=json.load(open(sys.argv[1])); b=json.load(open(sys.argv[2])); \
assert b['continuation_step_factor'] == 0.5 and abs(b['results'][0]['cage_speed_rad_s'] / \
a['results'][1]['cage_speed_rad_s'] - 1) < 1e-6, (a['results'][1]['cage_speed_rad_s'], b['results'][0])" \
      "$out/stability.json" "$out/half/stability.json" || fail "half steps: another steady state"
    "$exe" stability "$src/examples/reference_ball.toml" --continuation-steps 0 -o "$out/zero" > "$out/zero.log" 2>&1
    [ $? -eq 2 ] || fail "factor 0 accepted: $(cat "$out/zero.log")"
    grep -q -- "--continuation-steps must lie in (0, 1]" "$out/zero.log" || fail "factor 0: $(cat "$out/zero.log")"
    "$exe" stability "$src/examples/reference_floating_ring.toml" --speeds "50000 rpm" -o "$out/fr" > "$out/fr.log" 2>&1
    [ $? -eq 2 ] || fail "floating rings accepted: $(cat "$out/fr.log")"
    grep -q "bearing '.*': its element has no steady state" "$out/fr.log" || fail "message: $(cat "$out/fr.log")"
    # A steady state the iteration cannot find (with mu_0 = 0.01, mu_r = 0.005 the traction cannot carry the balls'
    # gyroscopic moment from about 23,000 rpm; docs/ball-bearing.md) ends the analysis there: the message names the
    # element and the speed, the speed before it is written, marked incomplete, exit 3.
    "$exe" stability "$src/examples/reference_ball.toml" --speeds "20000, 40000 rpm" -o "$out/planar" --no-plots \
      --set bearings.compressor.friction_static=0.01 --set bearings.compressor.friction_sliding=0.005 \
      --set bearings.turbine.friction_static=0.01 --set bearings.turbine.friction_sliding=0.005 \
      > "$out/planar.log" 2>&1
    [ $? -eq 3 ] || fail "no exit 3 without a steady state: $(cat "$out/planar.log")"
    grep -q "incomplete, .* at 40000 rpm: element 'compressor': no steady state found at [0-9]* rpm" "$out/planar.log" \
      || fail "message: $(cat "$out/planar.log")"
    python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert not j['complete'] and \
len(j['results'])==1 and j['results'][0]['speed_rpm']==20000 and 'at 40000 rpm' in j['stopped'], j['stopped']" \
      "$out/planar/stability.json" || fail "partial stability.json"
    grep -q "INCOMPLETE: no steady state" "$out/planar/report.html" || fail "report: incomplete"
    ;;
  failed_write)
    # Issue 20: a result file that cannot be written (here a directory is in its place) is an error naming it,
    # with a non-zero exit and no "Wrote" line.
    mkdir -p "$out/modal.json"
    "$exe" modal "$src/examples/reference_linear.toml" --no-plots -o "$out" > "$out/log" 2>&1
    rc=$?
    [ $rc -ne 0 ] || fail "exit 0 with modal.json a directory: $(cat "$out/log")"
    grep -q "cannot write .*modal.json" "$out/log" || fail "message: $(cat "$out/log")"
    ! grep -q "Wrote" "$out/log" || fail "claims to have written: $(cat "$out/log")"
    ;;
  modal_bad_input)
    # Issue 20: no crash (2^31 speeds), no endless loop (a speed of 1e308 rad/s), no raw "stoi".
    expect_refused() {  # expect_refused PATTERN COMMAND...: exit 2 within 20 s and a message matching PATTERN
      local pattern=$1; shift
      timeout 20 "$@" > "$out/log" 2>&1
      local rc=$?
      [ $rc -eq 2 ] || fail "exit $rc, expected 2 for: $* -- $(cat "$out/log")"
      grep -q -- "$pattern" "$out/log" || fail "message for: $* -- $(cat "$out/log")"
      ! grep -q -e "stoi" -e "bad_alloc" -e "_M_default_append" "$out/log" || fail "raw message: $(cat "$out/log")"
    }
    model="$src/examples/reference_linear.toml"
    expect_refused "--set modal.n_speeds=2147483648: modal.n_speeds: must be a whole number from 2 to" \
      "$exe" modal "$model" --set modal.n_speeds=2147483648 -o "$out/m" --no-plots
    expect_refused "--speeds '0:1e308:3': 1e+308 rad/s is implausibly large" \
      "$exe" modal "$model" --speeds 0:1e308:3 -o "$out/m" --no-plots
    expect_refused "COUNT must be a whole number from 2 to 100000" \
      "$exe" modal "$model" --speeds "0:100 Hz:99999999999999999999" -o "$out/m" --no-plots
    expect_refused "bearings.left.kxx: 1e+306 N/m is implausibly large" \
      "$exe" modal "$src/examples/friswell_5_9_1.toml" --set "bearings.left.kxx=1e+306 N/m" -o "$out/m" --no-plots
    ;;
  check_bad_input)
    # Issue 20: a tiny mesh is refused with its element count (it took 2 GB, then "std::bad_alloc"); a
    # directory is not a model file; NaN and infinity never reach the summary.
    timeout 20 "$exe" check "$src/examples/reference_linear.toml" --set "mesh.max_element_length=1e-9 m" > "$out/log" 2>&1
    [ $? -eq 2 ] || fail "tiny mesh: $(cat "$out/log")"
    grep -q "mesh.max_element_length: the shaft of 0.14 m in elements of at most 1e-09 m needs about 1.4e+08 elements" \
      "$out/log" || fail "tiny mesh message: $(cat "$out/log")"
    "$exe" check "$src/examples" > "$out/log" 2>&1
    [ $? -eq 2 ] && grep -q "examples: is a directory, not a model file" "$out/log" || fail "directory: $(cat "$out/log")"
    # A study file where a model file belongs names the command that runs it.
    "$exe" run "$src/examples/study_reference_linear.toml" -o "$out/study" > "$out/log" 2>&1
    [ $? -eq 2 ] && grep -q "study_reference_linear.toml: this is a study file (\[study\]), not a model file: run it with turbodyn sweep" \
      "$out/log" || fail "study file: $(cat "$out/log")"
    for set in "shaft[0].length=1e308" "shaft[0].outer_diameter=1e-299 mm" "materials.steel.rho=1.8e308"; do
      "$exe" check "$src/examples/reference_linear.toml" --set "$set" > "$out/log" 2>&1
      [ $? -eq 2 ] || fail "$set accepted: $(cat "$out/log")"
      grep -q -i -e "nan" -e "inf" "$out/log" && fail "$set: $(cat "$out/log")"
      grep -q -F -- "--set ${set%%=*}" "$out/log" || fail "$set: the message does not name the override: $(cat "$out/log")"
    done
    ;;
  journal_bad_input)
    # Issue 20: a huge attitude angle ran for ever; a bad grid gave the film solver's raw message.
    timeout 10 "$exe" journal --ld 0.7 --attitude 1e308 > "$out/log" 2>&1 || fail "attitude 1e308: exit $?: $(cat "$out/log")"
    grep -q '"attitude_angle_deg"' "$out/log" || fail "no result: $(cat "$out/log")"
    "$exe" journal --ld 1 --n-circ -5 > "$out/log" 2>&1
    [ $? -eq 2 ] && grep -q -- "--n-circ -5 --n-axial" "$out/log" || fail "grid: $(cat "$out/log")"
    ! grep -q "FilmSolver" "$out/log" || fail "raw message: $(cat "$out/log")"
    ;;
  sweep_bad_study)
    # Issue 20: studies that ran and gave nothing useful are refused before the first run, naming the key.
    study="$src/examples/study_reference_linear.toml"
    variant() {  # variant NAME SED-SCRIPT: the example study with an edit, its model given by absolute path
      sed -e "s|^model = .*|model = \"$src/examples/reference_linear.toml\"|" -e "$2" "$study" > "$out/$1.toml"
    }
    refused() {  # refused NAME PATTERN
      timeout 60 "$exe" sweep "$out/$1.toml" -o "$out/$1" --no-plots > "$out/$1.log" 2>&1
      local rc=$?
      [ $rc -eq 2 ] || fail "$1: exit $rc, expected 2: $(cat "$out/$1.log")"
      grep -q -- "$2" "$out/$1.log" || fail "$1: message: $(cat "$out/$1.log")"
      [ ! -f "$out/$1/runs.jsonl" ] || [ "$(wc -l < "$out/$1/runs.jsonl")" -le 1 ] || fail "$1: runs were made"
    }
    variant name 's|^path = "disks.turbine.unbalance"|path = "name"|'
    refused name "parameters\[0\].path: 'name' is not a number the model reference_linear.toml reads"
    variant summary 's|^probe = "stats.steps"|probe = "stats.stepz"|'
    refused summary "metrics\[4\].probe: the run summary has no value 'stats.stepz'; did you mean 'stats.steps'?"
    variant duplicate 's|^name = "steps"|name = "peak_1x_turbine"|'
    refused duplicate "metrics\[4\].name: metrics\[2\] has the name 'peak_1x_turbine' already"
    variant window 's|^speed_window = .*|speed_window = ["200000 rpm", "300000 rpm"]|'
    refused window "speed_window: \[200000, 300000\] rpm lies outside the speeds of the run"
    variant nan 's|^high = "870 mg\*mm"|high = nan|'
    refused nan "parameters\[0\].high: value is not finite"
    ;;
  *) fail "unknown case" ;;
esac
echo "PASS ($case)"
