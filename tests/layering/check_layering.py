#!/usr/bin/env python3
"""The layering of ../shared/DESIGN.md ("Folders"), checked on every #include.

1. A file in folder F includes project headers only from F itself and from the folders F may
   use (ALLOWED below: the DESIGN table's "may use" column). Dependencies point down, so a
   folder that includes one above it fails.
2. Only render/ sees Vulkan: no file of another library folder includes <vulkan/...> or a
   render/ header that includes Vulkan, directly or through other project headers. render's
   public headers (what scene/ and app/ include) are therefore plain data.
3. flight/ (paths, record tables, summaries, plots) includes no image library.

Usage: check_layering.py PROJECT_ROOT. Prints one line per violation (file:line: what) and
exits 1 if there is any; 0 and a one-line summary otherwise.
"""
import os
import re
import sys

ALLOWED = {
    "core": set(),
    "geo": {"core"},
    "datasets": {"geo", "core"},
    "streaming": {"datasets", "geo", "core"},
    # DESIGN.md lists streaming, geo, core; terrain also reads the dataset format's tile
    # constants and metadata (datasets/dataset_format.h) that streaming hands it.
    "terrain": {"streaming", "datasets", "geo", "core"},
    "vegetation": {"geo", "core"},
    "simulation": {"core"},
    "render": {"terrain", "vegetation", "simulation", "streaming", "geo", "core"},
    "flight": {"geo", "core"},
    "scene": {"render", "flight", "simulation", "vegetation", "terrain", "streaming", "datasets", "geo", "core"},
    "app": {"scene", "render", "flight", "simulation", "vegetation", "terrain", "streaming", "datasets", "geo",
            "core"},
}
FOLDERS = set(ALLOWED)
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
IMAGE_LIBRARIES = ("OpenImageIO/", "png.h", "jpeglib.h", "tiffio.h")


def sources(root):
    for folder in sorted(FOLDERS):
        base = os.path.join(root, folder)
        for dirpath, _, names in os.walk(base):
            for name in sorted(names):
                if name.endswith((".h", ".hpp", ".cpp", ".cc", ".in")):
                    yield folder, os.path.join(dirpath, name)


def includes(path):
    out = []
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                out.append((number, m.group(1), m.group(2)))
    return out


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    files = list(sources(root))
    parsed = {path: includes(path) for _, path in files}

    # Project headers that reach <vulkan/...>, through any chain of project includes.
    memo = {}

    def reaches_vulkan(header, seen=()):
        if header in memo:
            return memo[header]
        path = os.path.join(root, header)
        if header in seen or not os.path.exists(path):
            return False
        result = False
        for _, kind, name in parsed.get(path) or includes(path):
            if name.startswith("vulkan/"):
                result = True
            elif kind == '"' and name.split("/")[0] in FOLDERS and reaches_vulkan(name, seen + (header,)):
                result = True
            if result:
                break
        memo[header] = result
        return result

    problems = []
    checked = 0
    for folder, path in files:
        rel = os.path.relpath(path, root)
        for number, kind, name in parsed[path]:
            checked += 1
            top = name.split("/")[0]
            where = f"{rel}:{number}"
            if kind == '"' and top in FOLDERS and top != folder and top not in ALLOWED[folder]:
                problems.append(f"{where}: {folder}/ includes {name}, but {folder}/ may use only "
                                f"{', '.join(sorted(ALLOWED[folder])) or 'nothing'} (DESIGN.md: dependencies point down)")
            if folder != "render":
                if name.startswith("vulkan/"):
                    problems.append(f"{where}: includes <{name}>: only render/ sees Vulkan")
                elif kind == '"' and top == "render" and reaches_vulkan(name):
                    problems.append(f"{where}: includes {name}, which includes Vulkan: only render/ sees Vulkan "
                                    "(render's public headers are plain data)")
            if folder == "flight" and name.startswith(IMAGE_LIBRARIES):
                problems.append(f"{where}: flight/ includes the image library header {name}")
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} layering violations in {len(files)} files")
        return 1
    print(f"layering: {len(files)} files, {checked} includes, no folder includes one above it, only render/ sees Vulkan")
    return 0


if __name__ == "__main__":
    sys.exit(main())
