#!/usr/bin/env python3
"""The layering check fails where it must: a small tree with one violation of each rule."""
import os
import subprocess
import sys
import tempfile

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_layering.py")
FILES = {
    "core/ok.h": '#pragma once\n',
    "terrain/up.cpp": '#include "render/renderer.h"\n',               # terrain may not use render
    "render/renderer.h": '#include "render/context.h"\n',              # public header reaching Vulkan…
    "render/context.h": '#include <vulkan/vulkan.h>\n',
    "scene/scene.h": '#include "render/renderer.h"\n',                 # …so scene/ sees Vulkan
    "app/direct.cpp": '#include <vulkan/vulkan_core.h>\n',
    "flight/plot.cpp": '#include <OpenImageIO/imageio.h>\n',
    "geo/fine.cpp": '#include "core/ok.h"\n',
}
EXPECTED = ["terrain/up.cpp:1", "scene/scene.h:1", "app/direct.cpp:1", "flight/plot.cpp:1"]

with tempfile.TemporaryDirectory() as root:
    for name, text in FILES.items():
        os.makedirs(os.path.join(root, os.path.dirname(name)), exist_ok=True)
        with open(os.path.join(root, name), "w") as f:
            f.write(text)
    r = subprocess.run([sys.executable, CHECK, root], capture_output=True, text=True)
    failures = []
    if r.returncode != 1:
        failures.append(f"exit code {r.returncode}, expected 1")
    for where in EXPECTED:
        if where not in r.stdout:
            failures.append(f"{where} not reported")
    if "geo/fine.cpp" in r.stdout or "render/context.h" in r.stdout:
        failures.append("a permitted include was reported")
    if failures:
        print(r.stdout)
        print("\n".join(failures))
        sys.exit(1)
    print(f"the check reports all {len(EXPECTED)} planted violations and nothing else")
