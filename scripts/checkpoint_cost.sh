#!/usr/bin/env bash
# What a checkpoint of `soak simulate` costs: its size and the time to write
# one, for the busy wet-crate scene (wetting, radiation, a sea) and for the
# world of `soak bench` (1,000 bodies, half boxes 1.0 × 0.6 × 0.8 m and half
# spheres r = 0.5 m at 500 kg/m³, 128² atlases, on calm water 2 m apart).
# The last line `soak simulate` prints says both.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p soak-cli -q
soak=target/release/soak
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "== data/scenes/wet_crate.toml (12 s)"
(cd "$dir" && "$OLDPWD/$soak" simulate "$OLDPWD/data/scenes/wet_crate.toml" --duration 12 \
  --checkpoint wet.ckpt --checkpoint-every 6 | tail -1)
python3 - "$dir/fleet.toml" <<'PY'
import sys
lines = ["dt = 0.0166667", "duration = 0.1", "", "[water]", 'kind = "plane"', "level = 0.0", ""]
for i in range(1000):
    x, z = 2.0 * (i % 32), 2.0 * (i // 32)
    if i % 2 == 0:
        mesh, y = "builtin:box:1x0.6x0.8", 0.0
    else:
        mesh, y = "builtin:sphere:0.5", 0.0
    lines += ["[[bodies]]", f'name = "b{i}"', f'mesh = "{mesh}"', "resolution = 128",
              'mass = { model = "solid", density = 500.0 }', f"position = [{x}, {y}, {z}]", ""]
open(sys.argv[1], "w").write("\n".join(lines))
PY
echo "== 1,000 bodies (the bench's world), 0.1 s"
(cd "$dir" && "$OLDPWD/$soak" simulate fleet.toml --checkpoint fleet.ckpt | tail -1)
