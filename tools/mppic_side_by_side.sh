#!/usr/bin/env bash
# The side-by-side of CFD-DEM and MP-PIC in docs/validation/mppic.md: one fluidized bed, the
# default scene (scenes/fluidized_bed.ini, 800 beads of 3 mm) by CFD-DEM and its twin
# scenes/parcels_fluidized_bed.ini by MP-PIC at several beads per parcel, each from several
# seeds, over the same 5 s on one thread; or (--bed wide) the same bed four times as wide, 3200
# beads. From each run (1-5 s): the mean pressure drop, bed height
# (95 % of the beads below it) and mean height; the probe signal's (pressure between 10 and
# 50 mm above the floor) dominant frequency and rms, the slugs' mark; the solids fraction against
# height from the particle positions (gas-cell layers, solids volume over layer volume, averaged
# over the snapshots); the CPU and wall seconds per simulated second. Each run's errors against the
# reference, the CFD-DEM runs' mean (a CFD-DEM run against the mean of the others, to show the
# seed-to-seed level); the table (printed), PREFIX.csv, PREFIX_profile.csv and three plots,
# PREFIX.png (work-precision), PREFIX_profile.png and PREFIX_signal.png, with PREFIX mppic or
# mppic_wide.
#
# usage: tools/mppic_side_by_side.sh [--bed default|wide] [--bedlam PATH] [--runs DIR]
#                                    [--docs DIR] [--sizes "1 2 4 8"] [--seeds "1 2 3"]
#                                    [--no-extras] [--fresh]
#   --bed      default: the default scene's bed; wide: the same, 0.24 m wide (32 cells across)
#   --bedlam   the bedlam binary (default build/bedlam)
#   --runs     where the runs go (default runs/mppic_side_by_side/BED); finished runs are
#              reused unless --fresh
#   --docs     where the tables and plots go (default docs/validation)
#   --sizes    beads per parcel (default 1 2 4 8)
#   --seeds    seeds of every series (default 1 2 3; wide: 1 2)
#   --no-extras  leave out the series that explain the differences: CFD-DEM without friction,
#              MP-PIC with the CFD-DEM kernel's width, MP-PIC with model B's collisions (the
#              wide bed has none)
# Every run is done twice, without and with particle files (run below); one simulation at a
# time, each on one thread. About 5 minutes of CPU for the default bed, 6 for the wide one.
# Needs bash, awk, python3 (standard library) and gnuplot.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bedlam=$root/build/bedlam
bed=default
runs=""
docs=$root/docs/validation
sizes="1 2 4 8"
seeds=""
extras=1
fresh=0
while [ $# -gt 0 ]; do
  case $1 in
    --bed) bed=$2; shift 2 ;;
    --bedlam) bedlam=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --docs) docs=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --no-extras) extras=0; shift ;;
    --fresh) fresh=1; shift ;;
    *) echo "usage: $0 [--bed default|wide] [--bedlam PATH] [--runs DIR] [--docs DIR]" \
            "[--sizes LIST] [--seeds LIST] [--no-extras] [--fresh]" >&2
       exit 2 ;;
  esac
done
dem_scene=$root/scenes/fluidized_bed.ini
mppic_scene=$root/scenes/parcels_fluidized_bed.ini
spacing=0.0030003 # the scenes' lattice spacing [m]; one site deep: N beads a parcel, sqrt(N) it
case $bed in
  default)
    prefix=mppic
    width=0.06
    beads=800
    bed_sets=()
    dem_sets=()
    : "${seeds:=1 2 3}"
    ;;
  wide) # four times as wide: 79 beads a row instead of 19, about as many rows
    prefix=mppic_wide
    width=0.24
    beads=3200
    bed_sets=(--set "domain.max=0.24 0.0045 0.25" --set "gas.cells=32 1 33"
              --set "create.bed.region_max=0.2399 0.0044 0.2")
    dem_sets=(--set "wall.slot.max=0.24 0.0045 0.25" --set create.bed.count=3200)
    extras=0
    : "${seeds:=1 2}"
    ;;
  *) echo "--bed: default or wide, not '$bed'" >&2; exit 2 ;;
esac
: "${runs:=$root/runs/mppic_side_by_side/$bed}"
mkdir -p "$runs" "$docs"
common=(--threads 1 --quiet --set output.frame_interval=0 --set output.diagnostics_interval=0.005)
series_list=$runs/series.txt
: >"$series_list"

# run NAME SCENE [--set ...]: one simulation twice, unless finished ones are there: NAME without
# particle files, timed (its CPU seconds in NAME/cpu_seconds), and NAME.vtk with the positions
# every 0.025 s (writing them takes longer than stepping the parcels). The two are the same run:
# the outputs do not change the steps.
run() {
  local name=$1 scene=$2
  shift 2
  local out
  for out in "$runs/$name" "$runs/$name.vtk"; do
    if [ $fresh = 0 ] && [ -f "$out/run.log" ] && grep -q '^finished at' "$out/run.log"; then
      echo "$(basename "$out"): reused"
      continue
    fi
    rm -rf "$out"
    echo "$(basename "$out"): running"
    local vtk=0
    [ "$out" = "$runs/$name" ] || vtk=0.025
    python3 - "$out" "$bedlam" run "$scene" --out "$out" "${common[@]}" \
      --set output.vtk_interval=$vtk "$@" <<'CPU'
import resource, subprocess, sys
code = subprocess.call(sys.argv[2:])
use = resource.getrusage(resource.RUSAGE_CHILDREN)
with open(sys.argv[1] + "/cpu_seconds", "w") as f:
    f.write("%.3f\n" % (use.ru_utime + use.ru_stime))
sys.exit(code)
CPU
  done
}

# series LABEL METHOD BEADS_PER_PARCEL SCENE [--set ...]: one run per seed; listed for the
# analysis as label, method, beads per parcel, run folders.
series() {
  local label=$1 method=$2 n=$3 scene=$4
  shift 4
  local dirs=""
  for s in $seeds; do
    run "${label}_s$s" "$scene" --set run.seed="$s" "$@"
    dirs="$dirs ${label}_s$s"
  done
  echo "$label $method $n$dirs" >>"$series_list"
}

parcels_of() { # the overrides for N beads a parcel: the same solids, the same lattice height
  local n=$1
  local h
  h=$(awk -v s=$spacing -v n="$n" 'BEGIN { printf "%.7f", s * sqrt(n) }')
  echo "--set species.glass.parcel_particles=$n --set create.bed.count=$((beads / n))" \
       "--set create.bed.spacing=$h"
}

series dem cfd-dem 1 "$dem_scene" "${bed_sets[@]}" "${dem_sets[@]}"
for n in $sizes; do
  # shellcheck disable=SC2046
  series "mppic_n$n" mp-pic "$n" "$mppic_scene" "${bed_sets[@]}" $(parcels_of "$n")
done
if [ $extras = 1 ]; then
  # The contact network's share: the same CFD-DEM bed without friction (beads and walls).
  series dem_frictionless cfd-dem 1 "$dem_scene" --set species.glass.friction=0
  # The coupling kernel's share: MP-PIC with the CFD-DEM scene's kernel half-width (1.5 cells).
  # shellcheck disable=SC2046
  series mppic_n1_kernel mp-pic 1 "$mppic_scene" $(parcels_of 1) --set coupling.kernel_width=0.0114
  # Model B: soft spheres between parcels (a linear spring of 800 N/m, e = 0.9) instead of the
  # stress; the lattice opened to 1.08 diameters, beyond the spheres' reach (1.075), and the
  # drift in 10 parts (a contact lasts about 0.5 ms).
  series mppic_n1_collisions mp-pic 1 "$mppic_scene" --set parcels.model=collisions \
    --set parcels.collision_exponent=1 --set parcels.substeps=10 --set create.bed.spacing=0.00324
fi

python3 - "$runs" "$docs" "$series_list" "$prefix" "$width" <<'PY'
import cmath, csv, math, os, re, struct, sys

runs, docs, series_file, prefix = sys.argv[1:5]
T0, T1 = 1.0, 5.0          # the window of the time means [s]
FMIN, FMAX, DF = 0.2, 20.0, 0.01  # the probe spectrum's search band and grid [Hz]
AREA = float(sys.argv[5]) * 0.0045  # the floor [m^2]
HEIGHT, LAYERS = 0.25, 33  # the domain's height [m] and its gas layers


def diagnostics(run):
    with open(os.path.join(runs, run, "diagnostics.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return rows


def mean(xs):
    return sum(xs) / len(xs)


def std(xs):
    m = mean(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / len(xs))


def spectrum(t, x):
    """Power of x(t) (mean removed, Hamming window) on the grid FMIN..FMAX step DF."""
    n, m = len(x), mean(x)
    w = [(0.54 - 0.46 * math.cos(2 * math.pi * j / (n - 1))) * (x[j] - m) for j in range(n)]
    out = []
    k = 0
    while FMIN + k * DF <= FMAX + 1e-9:
        f = FMIN + k * DF
        z = sum(wj * cmath.exp(-2j * math.pi * f * tj) for wj, tj in zip(w, t))
        out.append((f, abs(z) ** 2))
        k += 1
    return out


def vtp_heights(path):
    """Heights and real radii of the particles (parcels) of one .vtp file (raw appended)."""
    with open(path, "rb") as f:
        b = f.read()
    i = b.index(b'<AppendedData encoding="raw">')
    start = b.index(b"_", i) + 1
    head = b[:i].decode()
    offsets = {m.group(1): int(m.group(2))
               for m in re.finditer(r'Name="(\w+)"[^>]*offset="(\d+)"', head)}

    def array(name):
        o = start + offsets[name]
        nbytes = struct.unpack_from("<Q", b, o)[0]
        return struct.unpack_from("<%dd" % (nbytes // 8), b, o + 8)

    p = array("Points")
    return p[2::3], array("radius")


def profile(run, beads_per_parcel):
    """Solids fraction of each gas-cell layer from the positions, averaged over T0..T1."""
    dz = HEIGHT / LAYERS
    acc = [0.0] * LAYERS
    frames = 0
    with open(os.path.join(runs, run + ".vtk", "particles.pvd")) as f:
        for m in re.finditer(r'timestep="([^"]+)"[^>]*file="([^"]+)"', f.read()):
            if not (T0 - 1e-9 <= float(m.group(1)) <= T1 + 1e-9):
                continue
            z, r = vtp_heights(os.path.join(runs, run + ".vtk", m.group(2)))
            for zi, ri in zip(z, r):
                k = min(max(int(zi / dz), 0), LAYERS - 1)
                acc[k] += beads_per_parcel * 4.0 / 3.0 * math.pi * ri ** 3
            frames += 1
    return [a / (frames * AREA * dz) for a in acc]


def measure(run, n):
    rows = diagnostics(run)
    twin = diagnostics(run + ".vtk")[-1]
    for k in ("time", "bed_height", "pressure_drop"):
        if twin[k] != rows[-1][k]:
            print("warning: %s and %s.vtk differ in %s at the end" % (run, run, k), file=sys.stderr)
    with open(os.path.join(runs, run, "cpu_seconds")) as f:
        cpu = float(f.read())
    win = [r for r in rows if T0 - 1e-9 <= r["time"] <= T1 + 1e-9]
    t = [r["time"] for r in win]
    probe = [r["probe_pressure_drop"] for r in win]
    spec = spectrum(t, probe)
    f_peak, p_peak = max(spec, key=lambda s: s[1])
    total = sum(p for _, p in spec)
    near = sum(p for f, p in spec if abs(f - f_peak) <= 0.25)
    return {
        "wall": (rows[-1]["wall_seconds"] - rows[0]["wall_seconds"]) /
                (rows[-1]["time"] - rows[0]["time"]),
        "cpu": cpu / rows[-1]["time"],
        "dp": mean([r["pressure_drop"] for r in win]),
        "weight_ratio": mean([r["weight_ratio"] for r in win]),
        "bed_height": mean([r["bed_height"] for r in win]),
        "mean_height": mean([r["mean_height"] for r in win]),
        "freq": f_peak,
        "peak_share": near / total,
        "rms": std(probe),
        "out": rows[-1]["particles_out"] * n,
        "profile": profile(run, n),
        "signal": [(r["time"], r["probe_pressure_drop"]) for r in rows],
    }


SCALARS = ["dp", "bed_height", "freq", "rms", "mean_height"]


def errors(m, ref):
    e = {k: (m[k] - ref[k]) / ref[k] for k in SCALARS}
    num = sum((a - b) ** 2 for a, b in zip(m["profile"], ref["profile"]))
    den = sum(b ** 2 for b in ref["profile"])
    e["profile"] = math.sqrt(num / den)
    return e


def average(ms):
    a = {k: mean([m[k] for m in ms]) for k in SCALARS + ["wall", "cpu", "weight_ratio",
                                                           "peak_share", "out"]}
    a["profile"] = [mean(col) for col in zip(*[m["profile"] for m in ms])]
    return a


series = []
with open(series_file) as f:
    for line in f:
        label, method, n, *dirs = line.split()
        print("measuring", label, file=sys.stderr)
        series.append({"label": label, "method": method, "n": int(n),
                       "runs": [measure(d, int(n)) for d in dirs]})
dem = next(s for s in series if s["label"] == "dem")
ref = average(dem["runs"])
for s in series:
    s["mean"] = average(s["runs"])
    s["std"] = {k: std([m[k] for m in s["runs"]])
                for k in SCALARS + ["wall", "cpu", "weight_ratio"]}
    if s is dem:  # each CFD-DEM run against the mean of the others: the seed-to-seed level
        per = [errors(m, average([o for o in dem["runs"] if o is not m])) for m in dem["runs"]]
    else:
        per = [errors(m, ref) for m in s["runs"]]
    s["abs_err"] = {k: mean([abs(e[k]) for e in per]) for k in SCALARS + ["profile"]}
    s["err_of_mean"] = errors(s["mean"], ref)

keys = ["dp", "bed_height", "freq", "rms", "profile", "mean_height"]
with open(os.path.join(docs, prefix + ".csv"), "w") as f:
    f.write("series,method,beads_per_parcel,seeds,wall_per_simulated_second,"
            "cpu_per_simulated_second,pressure_drop,"
            "weight_ratio,bed_height,mean_height,probe_frequency,probe_peak_share,probe_rms,"
            "beads_out," + ",".join("error_" + k for k in keys) + "," +
            ",".join("error_of_mean_" + k for k in keys) + "\n")
    for s in series:
        m = s["mean"]
        f.write("%s,%s,%d,%d,%.4g,%.4g,%.5g,%.4g,%.5g,%.5g,%.4g,%.3g,%.4g,%.3g,%s,%s\n" % (
            s["label"], s["method"], s["n"], len(s["runs"]), m["wall"], m["cpu"], m["dp"],
            m["weight_ratio"], m["bed_height"], m["mean_height"], m["freq"], m["peak_share"],
            m["rms"], m["out"], ",".join("%.4g" % s["abs_err"][k] for k in keys),
            ",".join("%.4g" % s["err_of_mean"][k] for k in keys)))
with open(os.path.join(docs, prefix + "_profile.csv"), "w") as f:
    f.write("height," + ",".join(s["label"] for s in series) + "\n")
    for k in range(LAYERS):
        f.write("%.5g," % ((k + 0.5) * HEIGHT / LAYERS) +
                ",".join("%.4g" % s["mean"]["profile"][k] for s in series) + "\n")
with open(os.path.join(runs, "signal.csv"), "w") as f:  # the first seed's probe signals
    f.write("time," + ",".join(s["label"] for s in series) + "\n")
    for rows in zip(*[s["runs"][0]["signal"] for s in series]):
        f.write("%.4f," % rows[0][0] + ",".join("%.2f" % r[1] for r in rows) + "\n")
with open(os.path.join(runs, "work_precision.csv"), "w") as f:  # the plot's data
    f.write("series,beads_per_parcel,wall,cpu," + ",".join("error_" + k for k in keys) + "\n")
    for s in series:
        f.write("%s,%d,%.4g,%.4g," % (s["label"], s["n"], s["mean"]["wall"], s["mean"]["cpu"]) +
                ",".join("%.4g" % s["abs_err"][k] for k in keys) + "\n")


def pm(s, k, scale, fmt):
    return (fmt + " ± " + fmt) % (scale * s["mean"][k], scale * s["std"][k])


def pct(x):
    return "%+.0f %%" % (100 * x)


NAMES = {"dem": "CFD-DEM (reference)", "dem_frictionless": "CFD-DEM without friction",
         "mppic_n1_kernel": "MP-PIC, kernel 1.5 cells", "mppic_n1_collisions": "MP-PIC, model B"}
print("| series | N | wall (CPU) s per simulated s | Δp [Pa] | Δp / weight | bed height [mm] | "
      "mean height [mm] | probe frequency [Hz] | peak share | probe rms [Pa] | profile L2 | "
      "beads out |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for s in series:
    e = s["err_of_mean"] if s is not dem else None

    def cell(k, scale, fmt):
        txt = pm(s, k, scale, fmt)
        if e is None:
            return txt + " (±%.0f %%)" % (100 * s["abs_err"][k])
        return txt + " (" + pct(e[k]) + ")"
    prof = ("%.3f" % s["abs_err"]["profile"]) if e is None else ("%.3f" % e["profile"])
    print("| %s | %d | %s | %s | %s | %s | %s | %s | %.2f | %s | %s | %.0f |" % (
        NAMES.get(s["label"], "MP-PIC"), s["n"],
        pm(s, "wall", 1, "%.2f") + " (%.2f)" % s["mean"]["cpu"], cell("dp", 1, "%.0f"),
        pm(s, "weight_ratio", 1, "%.3f"), cell("bed_height", 1000, "%.1f"),
        cell("mean_height", 1000, "%.1f"), cell("freq", 1, "%.2f"), s["mean"]["peak_share"],
        cell("rms", 1, "%.0f"), prof, s["mean"]["out"]))
print()
print("reference (CFD-DEM, %d seeds): Δp %.1f Pa (weight ratio %.4f), bed height %.2f mm, "
      "mean height %.2f mm, probe %.2f Hz, rms %.1f Pa, %.3f wall s per simulated s" % (
          len(dem["runs"]), ref["dp"], ref["weight_ratio"], 1000 * ref["bed_height"],
          1000 * ref["mean_height"], ref["freq"], ref["rms"], ref["wall"]))
print("mean |error| of one run (CFD-DEM: against the mean of the other seeds):")
for s in series:
    print("  %-20s wall %.3f cpu %.3f  " % (s["label"], s["mean"]["wall"], s["mean"]["cpu"]) +
          "  ".join("%s %.3f" % (k, s["abs_err"][k]) for k in keys) +
          "  weight ratio %.4f  mean height %.2f mm" % (s["mean"]["weight_ratio"],
                                                        1000 * s["mean"]["mean_height"]))
PY

# The plots: work-precision (the error of one run against its cost: the CPU time of the one
# thread per simulated second, which is its wall time on a core of its own), the solids fraction
# against height, and the probe signals of the first seed.
labels=$(awk '{ print $1 }' "$series_list")
wp=$runs/work_precision.csv
sizes_csv=$(echo "$sizes" | awk '{ $1 = $1; gsub(/ /, ","); print }')
gnuplot <<GP
set terminal pngcairo size 980,600 font 'DejaVu Sans,11'
set output '$docs/$prefix.png'
set datafile separator ','
set logscale xy
set xlabel 'wall time per simulated second [s] (one thread, its CPU time)'
set ylabel 'error of one run against CFD-DEM'
set grid
set key outside right
set title '$bed bed: MP-PIC at N = $sizes_csv beads per parcel (labels) against CFD-DEM'
mp = '< grep -E "^mppic_n[0-9]+," $wp'
dem = '< grep -E "^dem," $wp'
odd(n) = int(log(n) / log(2) + 0.5) % 2
plot mp using 4:5 with linespoints lw 2 pt 7 lc rgb '#c03030' title 'MP-PIC: pressure drop', \\
     mp using 4:6 with linespoints lw 2 pt 7 lc rgb '#3060c0' title 'MP-PIC: bed height', \\
     mp using 4:7 with linespoints lw 2 pt 7 lc rgb '#30a030' title 'MP-PIC: probe frequency', \\
     mp using 4:8 with linespoints lw 2 pt 7 lc rgb '#a050c0' title 'MP-PIC: probe rms', \\
     mp using 4:9 with linespoints lw 2 pt 7 lc rgb '#d08020' title 'MP-PIC: profile (L2)', \\
     mp using 4:(odd(column(2)) ? column(6) : NaN):(sprintf('%d', column(2))) \\
       with labels offset 0,1 notitle, \\
     mp using 4:(odd(column(2)) ? NaN : column(6)):(sprintf('%d', column(2))) \\
       with labels offset 0,-1 notitle, \\
     dem using 4:5 with points pt 6 ps 2 lw 2 lc rgb '#c03030' title 'CFD-DEM seeds: pressure drop', \\
     dem using 4:6 with points pt 6 ps 2 lw 2 lc rgb '#3060c0' title 'CFD-DEM seeds: bed height', \\
     dem using 4:7 with points pt 6 ps 2 lw 2 lc rgb '#30a030' title 'CFD-DEM seeds: frequency', \\
     dem using 4:8 with points pt 6 ps 2 lw 2 lc rgb '#a050c0' title 'CFD-DEM seeds: probe rms', \\
     dem using 4:9 with points pt 6 ps 2 lw 2 lc rgb '#d08020' title 'CFD-DEM seeds: profile'
GP

prof=$docs/${prefix}_profile.csv
{
  cat <<GP
set terminal pngcairo size 640,560 font 'DejaVu Sans,11'
set output '$docs/${prefix}_profile.png'
set datafile separator ','
set xlabel 'solids fraction (positions, layers of the gas grid)'
set ylabel 'height [mm]'
set grid
set key top right
set yrange [0:230]
set title 'solids fraction against height, 1-5 s'
GP
  printf "plot "
  first=1
  for l in $labels; do
    [ $first = 1 ] || printf ", "
    first=0
    case $l in
      dem) style="lw 3 lc rgb 'black'" ;;
      dem_*) style="lw 2 dt 2 lc rgb 'black'" ;;
      mppic_n*_*) style="lw 2 dt 3" ;;
      *) style="lw 2" ;;
    esac
    printf "'%s' using (column('%s')):(1000*column('height')) with lines %s title '%s'" \
      "$prof" "$l" "$style" "$(echo "$l" | tr '_' ' ')"
  done
  printf "\n"
} >"$runs/profile.gp"
gnuplot "$runs/profile.gp"

sig=$runs/signal.csv
first=$(echo "$sizes" | awk '{ print $1 }')
last=$(echo "$sizes" | awk '{ print $NF }')
beads_a_parcel() { [ "$1" = 1 ] && echo "one_bead_a_parcel" || echo "${1}_beads_a_parcel"; }
panels="dem:CFD-DEM mppic_n$first:MP-PIC,_$(beads_a_parcel "$first")"
[ "$last" = "$first" ] || panels="$panels mppic_n$last:MP-PIC,_$(beads_a_parcel "$last")"
grep -q '^mppic_n1_collisions ' "$series_list" &&
  panels="$panels mppic_n1_collisions:MP-PIC_with_model_B's_collisions,_one_bead_a_parcel"
top=$(awk -F, 'NR == 1 { next } $1 >= 2 && $1 <= 4 { for (i = 2; i <= NF; i++) if ($i > m) m = $i }
               END { print 100 * int(m / 100 + 1) }' "$sig")
count=$(echo "$panels" | wc -w)
{
  cat <<GP
set terminal pngcairo size 900,$((40 + 200 * count)) font 'DejaVu Sans,11'
set output '$docs/${prefix}_signal.png'
set datafile separator ','
set multiplot layout $count,1
set grid
set xrange [2:4]
set yrange [0:$top]
set ylabel 'probe Δp [Pa]'
GP
  k=0
  for p in $panels; do
    k=$((k + 1))
    [ $k = "$count" ] && echo "set xlabel 'time [s]'"
    echo "set title \"$(echo "${p#*:}" | tr '_' ' ')\""
    echo "plot '$sig' using 1:(column('${p%%:*}')) with lines lw 1.5 lc rgb '#3060c0' notitle"
  done
  echo "unset multiplot"
} >"$runs/signal.gp"
gnuplot "$runs/signal.gp"
echo "wrote $prefix.csv, ${prefix}_profile.csv and the plots $prefix*.png in $docs"
