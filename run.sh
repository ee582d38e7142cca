#!/usr/bin/env bash
# fibrecheck on a fresh Debian machine:
#   ./run.sh        install what is missing, build into build/, run the default suite and the report
#   ./run.sh test   the same set-up, then the test suite (ctest)
set -euo pipefail
cd "$(dirname "$0")"

mode="${1:-main}"
case "$mode" in
  main|test) ;;
  *) echo "usage: ./run.sh [test]" >&2; exit 2 ;;
esac

# Debian packages the project builds and runs with.
packages=(build-essential cmake libeigen3-dev nlohmann-json3-dev libcli11-dev libgtest-dev
          libbenchmark-dev gnuplot-nox libdeal.ii-dev gmsh libgmsh-dev openmpi-bin
          libsiconos-numerics-dev libsuitesparse-dev texlive-latex-base texlive-latex-recommended
          texlive-latex-extra texlive-luatex lmodern poppler-utils)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "Missing Debian packages: ${missing[*]}" >&2
    echo "Install them with:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
  echo "Installing missing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$jobs"

if [ "$mode" = test ]; then
  cd build
  exec ctest --output-on-failure -j "$jobs"
fi

# The main job: every scene through the iterative solver (a summary table), then the default suite
# of the harness — compare on every committed scene, the slice study, the tolerance study, the
# stability study, the compaction study, the friction study and the scale study — and the report.
# Studies keep their points: an interrupted run resumes.
out=build/main
mkdir -p "$out" build/results
step() { echo; echo "== $*"; }
status=0
step "iterative solver on every committed scene"
./build/fibrecheck solve scenes/*.json --out-dir build/results -q || status=$?
./build/fibrecheck solve scenes/*.json --out-dir build/results | sed -n '/^scene  /,$p' || true
if ! ./build/fibrecheck fem --help >/dev/null 2>&1; then
  echo "This build has no finite-element stack: the comparison, the studies and the report need it."
  exit "$status"
fi
step "compare: both solvers on every committed scene"
./build/fibrecheck compare scenes/*.json --out "$out/compare" -q
./build/fibrecheck generate tow --fibres 100 --slices 100 --seed 3 --out "$out/scenes/tow_100.json" >/dev/null
# The studies measure against the same ground truths as the comparison: computed once.
for study in slices tolerance; do
  mkdir -p "$out/study/$study"
  for scene in parallel_fibres small_tow_19; do
    truth="$out/compare/$scene/reference_continuous.result.json"
    [ -f "$truth" ] && cp -n "$truth" "$out/study/$study/$scene.truth.result.json"
  done
done
step "slice study: parallel fibres"
./build/fibrecheck study slices scenes/parallel_fibres.json --slices 2,4,8,16,32,64,128 \
  --out "$out/study/slices"
step "tolerance study: small_tow_19 against the continuous reference"
./build/fibrecheck study tolerance scenes/small_tow_19.json --refinements 0,1,2 \
  --out "$out/study/tolerance"
step "tolerance study: a generated 100-fibre tow against the reference on its slices"
./build/fibrecheck study tolerance "$out/scenes/tow_100.json" --against-slices --tolerances 1e-3,1e-4,1e-5,1e-6 \
  --out "$out/study/tolerance_tow"
step "stability study: two crossing fibres, the parallel fibres and the extreme catalogue"
./build/fibrecheck study stability scenes/two_fibres_crossing.json scenes/parallel_fibres.json \
  scenes/extreme/*.json --max-iterations 50000 --out "$out/study/stability" -q
step "compaction study: the seed's compaction test case, generated tows of 19 and 100 fibres (mu = 0.2; the reference with friction on both)"
./build/fibrecheck generate tow --fibres 19 --seed 2 --volume-fraction 0.35 --steps 12 \
  --final-compaction 0.7 --friction 0.2 --out "$out/scenes/tow_19_compaction.json" >/dev/null
./build/fibrecheck generate tow --fibres 100 --slices 20 --seed 2 --volume-fraction 0.35 --steps 5 \
  --first-compaction 0.8 --final-compaction 0.7 --friction 0.2 \
  --out "$out/scenes/tow_100_compaction.json" >/dev/null
./build/fibrecheck study compaction scenes/compaction_test.json "$out/scenes/tow_19_compaction.json" \
  "$out/scenes/tow_100_compaction.json" --steps 6 --final-compaction 0.7 --sections 10 \
  --frictional-reference-fibres 100 --out "$out/study/compaction"
# The 1 000-fibre studies take more than an hour: their points are stored in benchmarks/stored/ and
# copied in; a folder without them runs them afresh.
step "compaction study: a generated 1 000-fibre tow, 12 steps from its first wall contact to Vf 0.65 (stored points)"
./build/fibrecheck generate tow --fibres 1000 --slices 100 --seed 2 --steps 12 --first-compaction 0.855 \
  --final-compaction 0.806 --friction 0.2 --out "$out/scenes/tow_1000_compaction.json" >/dev/null
mkdir -p "$out/study/compaction_1000" "$out/study/friction_1000"
cp -n benchmarks/stored/compaction_1000.points.jsonl "$out/study/compaction_1000/compaction_study.points.jsonl"
cp -n benchmarks/stored/friction_1000.points.jsonl "$out/study/friction_1000/friction_study.points.jsonl"
./build/fibrecheck study compaction "$out/scenes/tow_1000_compaction.json" --reference-fibres 100 \
  --out "$out/study/compaction_1000"
step "friction study: the seed's friction rule against Coulomb friction, tows of 19 and 100 fibres over mu and F, and of 1 000 (stored points) at F 0.9 and 0.8"
./build/fibrecheck study friction --fibres 19,100 --mu 0.1,0.2,0.4 --compactions 0.9,0.8,0.7 \
  --out "$out/study/friction" -q
./build/fibrecheck study friction --fibres 1000 --mu 0.1,0.2,0.4 --compactions 0.9,0.8 \
  --out "$out/study/friction_1000" -q
step "scale study: generated tows of 100 to 3000 fibres; the reference up to 1000 on two processes; Siconos at 100"
./build/fibrecheck study scale --fibres 100,300,1000,3000 --rules accelerated \
  --reference-fibres 100,300,1000 --peer-fibres 100 --out "$out/study/scale" -q
step "report"
./build/fibrecheck report "$out/compare" "$out/study" --out "$out/report"
# Twice: the second run sets the citations and references the first wrote down.
for _ in 1 2; do
  (cd "$out/report" && pdflatex -interaction=nonstopmode -halt-on-error report.tex >/dev/null) ||
    { echo "pdflatex stopped on $out/report/report.tex: see $out/report/report.log"; exit 1; }
done
echo
echo "The report: $out/report/report.pdf (Markdown: report.md, LaTeX: report.tex). Results of the scenes: build/results/."
exit 0
