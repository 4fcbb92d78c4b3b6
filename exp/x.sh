#!/bin/bash
bash .gpu/assemble >/dev/null 2>&1 || { echo assemble failed; exit 1; }
for run in a0:0 b200:200 c0:0 d200:200; do
  n=${run%%:*}; s=${run##*:}
  SPF=$s bench/gpu-measure --runner /tmp/vsb/run --dataset /tmp/vsb/extra/zion --out /tmp/m/$n --no-bench --only default >/dev/null 2>&1
  mkdir -p $OUT/$n && cp /tmp/m/$n/default/frames.csv $OUT/$n/ 2>/dev/null; tail -2 /tmp/m/$n/default.log
done
nproc; lscpu | grep "Model name"
