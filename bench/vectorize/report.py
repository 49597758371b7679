#!/usr/bin/python3
"""Tables of a scripts/bench.sh run: reads <work>/results.tsv, <work>/machine.txt and the timestamped
vectorize logs <work>/runs/<grid>_urbanvec_vectorize.log, prints Markdown tables to stdout and, with
--markdown FILE, writes them to FILE too.

Usage: report.py <work dir> [--markdown FILE]
"""
import csv
import os
import sys

VECTORIZE = "urbanvec_vectorize"
POLYGONIZE = "gdal_polygonize"
GRASS = "grass_r.to.vect"

# Progress stage names of `vectorize -progress lines`, grouped into the rows of the stage table.
ROAD_STAGES = "road network (A2-F)"
GROUPS = [
    ("pavement (C)", {"road geometry", "road geometry overlaps"}),
    ("blocks (D1-D5)", {"block outlining", "water", "external blocks", "water splitting", "block matching",
                        "blocks"}),
    ("road frontage (E2 input)", {"road frontage"}),
    ("spines, parcels (D6-E6)", {"parcels"}),
    ("city layers", {"city layers"}),
]
READ = "read input"
WRITE = "write output"


def load_results(work):
    rows = {}
    order = []
    with open(os.path.join(work, "results.tsv"), newline="") as f:
        for r in csv.DictReader(f, delimiter="\t"):
            for k in ("wall_s", "user_s", "sys_s"):
                r[k] = float(r[k] or 0)
            for k in ("cells", "input_bytes", "peak_kb", "output_bytes", "status"):
                r[k] = int(r[k] or 0)
            r["cpu_s"] = r["user_s"] + r["sys_s"]
            if r["grid"] not in rows:
                rows[r["grid"]] = {}
                order.append(r["grid"])
            rows[r["grid"]][r["tool"]] = r
    return order, rows


def parse_log_line(line):
    """(wall, cpu, peak kB, resident kB, text) of a timestamp.py line (older logs lack the memory)."""
    parts = line.rstrip("\n").split(" ", 4)
    if len(parts) < 3:
        return None
    try:
        wall, cpu = float(parts[0]), float(parts[1])
        if len(parts) == 5 and parts[2].isdigit() and parts[3].isdigit():
            return wall, cpu, int(parts[2]), int(parts[3]), parts[4]
    except ValueError:
        return None
    return wall, cpu, 0, 0, line.rstrip("\n").split(" ", 2)[2]


def stage_times(log_path):
    """[(group, wall s, cpu s, peak kB at its end, resident kB at its end)] in pipeline order from a
    timestamped vectorize log."""
    if not os.path.exists(log_path):
        return []
    events = []  # (wall, cpu, peak, rss, stage) at each change of stage; stage None = end of stream
    for line in open(log_path):
        parsed = parse_log_line(line)
        if not parsed:
            continue
        wall, cpu, peak, rss, text = parsed
        if text == "EOF":
            events.append((wall, cpu, peak, rss, None))
        elif text.startswith("PROGRESS "):
            stage = text.split(" ", 2)[2] if text.count(" ") >= 2 else ""
            if not events:
                events.append((0.0, 0.0, 0, 0, READ))
            if events[-1][4] != stage:
                events.append((wall, cpu, peak, rss, stage))
    if not events or events[-1][4] is not None:
        return []
    totals = {}
    order = []
    seen_pavement = False
    for (w0, c0, _, _, stage), (w1, c1, p1, r1, _) in zip(events, events[1:]):
        if stage == "done":
            group = WRITE
        elif stage == READ:
            group = READ
        else:
            group = None
            for name, members in GROUPS:
                if stage in members and (seen_pavement or name == "pavement (C)"):
                    group = name
            if group == "pavement (C)":
                seen_pavement = True
            if group is None:
                group = ROAD_STAGES if not seen_pavement else stage
        if group not in totals:
            totals[group] = [0.0, 0.0, 0, 0]
            order.append(group)
        totals[group][0] += w1 - w0
        totals[group][1] += c1 - c0
        totals[group][2] = max(totals[group][2], p1)
        totals[group][3] = r1
    return [(g,) + tuple(totals[g]) for g in order]


def fmt(v, digits=2):
    return "%.*f" % (digits, v)


def ratio(a, b):
    return "%.1f" % (a / b) if b > 0 else "-"


def grid_label(name, cells):
    side = int(round(cells ** 0.5))
    return "%s (%s cells)" % (name, "%d²" % side if side * side == cells else "{:,}".format(cells))


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        sys.stderr.write(__doc__.split("\n\n")[-1] + "\n")
        return 2
    work = args[0]
    markdown = None
    if "--markdown" in args:
        markdown = args[args.index("--markdown") + 1]
    order, rows = load_results(work)
    out = []
    machine = {}
    mpath = os.path.join(work, "machine.txt")
    if os.path.exists(mpath):
        for line in open(mpath):
            if ":" in line:
                k, v = line.split(":", 1)
                machine[k.strip()] = v.strip()
    if machine:
        out.append("Machine: %s CPUs (%s), %s; load average %s at the start, %s at the end; %s; %s; %s." % (
            machine.get("cpus", "?"), machine.get("cpu", "?"), machine.get("memory", "?"),
            machine.get("load_start", "?"), machine.get("load_end", "?"), machine.get("urbanvec", ""),
            machine.get("gdal", ""), machine.get("grass", "no GRASS")))
        out.append("")

    has_grass = any(GRASS in rows[g] for g in order)
    # 1. End to end.
    out.append("### End to end: vectorize against the staircase baselines")
    out.append("")
    head = ["grid", "vectorize wall s", "CPU s", "CPU use", "gdal_polygonize wall s (CPU s)"]
    if has_grass:
        head.append("GRASS r.to.vect wall s (CPU s)")
    head += ["wall ÷ gdal", "CPU ÷ gdal"]
    if has_grass:
        head += ["wall ÷ GRASS", "CPU ÷ GRASS"]
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "---|" * len(head))
    for g in order:
        t = rows[g]
        v = t.get(VECTORIZE)
        p = t.get(POLYGONIZE)
        if not v:
            continue
        cells = v["cells"]
        line = [grid_label(g, cells), fmt(v["wall_s"]), fmt(v["cpu_s"]),
                "%d%%" % round(100 * v["cpu_s"] / v["wall_s"]) if v["wall_s"] > 0 else "-"]
        line.append("%s (%s)" % (fmt(p["wall_s"]), fmt(p["cpu_s"])) if p else "-")
        gr = t.get(GRASS)
        if has_grass:
            line.append("%s (%s)" % (fmt(gr["wall_s"]), fmt(gr["cpu_s"])) if gr else "-")
        line += [ratio(v["wall_s"], p["wall_s"]) if p else "-", ratio(v["cpu_s"], p["cpu_s"]) if p else "-"]
        if has_grass:
            line += [ratio(v["wall_s"], gr["wall_s"]) if gr else "-", ratio(v["cpu_s"], gr["cpu_s"]) if gr else "-"]
        if v["status"] != 0:
            line[0] += " FAILED"
        out.append("| " + " | ".join(line) + " |")
    out.append("")

    # 2. Memory.
    out.append("### Peak memory against input and output")
    out.append("")
    out.append("Input = the rasters as the program holds them (Byte land use, Float32 density, Int32 parcel "
               "ids) plus parcels.csv; output = the GeoPackage written; program = the resident size of "
               "`urbanvec vectorize --help` (code and libraries loaded, no data).")
    out.append("")
    idle = float(machine.get("urbanvec_idle_kb", "0") or 0) / 1024
    head = ["grid", "input MB", "output MB", "vectorize peak MB", "peak ÷ (input + output)",
            "(peak − %.0f MB program) ÷ (input + output)" % idle, "gdal_polygonize peak MB"]
    if has_grass:
        head.append("GRASS peak MB")
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "---|" * len(head))
    for g in order:
        t = rows[g]
        v = t.get(VECTORIZE)
        if not v:
            continue
        inp, outp, peak = v["input_bytes"] / 2**20, v["output_bytes"] / 2**20, v["peak_kb"] / 1024
        line = [grid_label(g, v["cells"]), fmt(inp, 1), fmt(outp, 1), fmt(peak, 0),
                ratio(peak, inp + outp), ratio(peak - idle, inp + outp),
                fmt(t[POLYGONIZE]["peak_kb"] / 1024, 0) if POLYGONIZE in t else "-"]
        if has_grass:
            line.append(fmt(t[GRASS]["peak_kb"] / 1024, 0) if GRASS in t else "-")
        out.append("| " + " | ".join(line) + " |")
    out.append("")

    # 3. Scaling.
    mirrored = [g for g in order if VECTORIZE in rows[g] and "_" in g]
    if mirrored:
        base = rows[mirrored[0]][VECTORIZE]
        base_wall = base["wall_s"] / base["cells"] * 1e6
        base_cpu = base["cpu_s"] / base["cells"] * 1e6
        out.append("### Scaling: time per million cells")
        out.append("")
        out.append("| grid | million cells | vectorize wall s / Mcell | CPU s / Mcell | wall per cell ÷ %s | "
                   "CPU per cell ÷ %s | gdal_polygonize wall s / Mcell |" % (mirrored[0], mirrored[0]))
        out.append("|---|---|---|---|---|---|---|")
        for g in mirrored:
            v = rows[g][VECTORIZE]
            p = rows[g].get(POLYGONIZE)
            mc = v["cells"] / 1e6
            wall, cpu = v["wall_s"] / mc, v["cpu_s"] / mc
            out.append("| %s | %.2f | %s | %s | %s | %s | %s |" % (
                grid_label(g, v["cells"]), mc, fmt(wall), fmt(cpu), fmt(wall / base_wall), fmt(cpu / base_cpu),
                fmt(p["wall_s"] / mc) if p else "-"))
        out.append("")

    # 4. Stages.
    stages = {g: stage_times(os.path.join(work, "runs", "%s_%s.log" % (g, VECTORIZE))) for g in order}
    names = []
    for g in order:
        for name in (st[0] for st in stages[g]):
            if name not in names:
                names.append(name)
    if names:
        shown = [g for g in order if stages[g]]

        def stage_table(title, cell):
            """One row per stage, one column per grid; cell(entries of that stage) -> text."""
            out.append(title)
            out.append("")
            out.append("| stage | " + " | ".join(grid_label(g, rows[g][VECTORIZE]["cells"]) for g in shown) + " |")
            out.append("|---|" + "---|" * len(shown))
            for name in names:
                out.append("| " + " | ".join([name] + [cell([st for st in stages[g] if st[0] == name])
                                                         for g in shown]) + " |")
            out.append("")

        def wall_cell(hit):
            if not hit:
                return "-"
            _, w, c, _, _ = hit[0]
            return "%s (%s)" % (fmt(w), "%d%%" % round(100 * c / w) if w >= 0.05 else "-")

        def memory_cell(hit):
            return "%.0f (%.0f)" % (hit[0][4] / 1024, hit[0][3] / 1024) if hit and hit[0][3] else "-"

        stage_table("### vectorize per stage: wall s (CPU use, 100% = one core busy)", wall_cell)
        if any(p for g in shown for _, _, _, p, _ in stages[g]):
            stage_table("### vectorize memory per stage: resident MB at the end of the stage (peak so far)",
                        memory_cell)

    # 5. Targets, on the largest grid.
    if mirrored:
        g = mirrored[-1]
        v = rows[g][VECTORIZE]
        p = rows[g].get(POLYGONIZE)
        inp, outp, peak = v["input_bytes"] / 2**20, v["output_bytes"] / 2**20, v["peak_kb"] / 1024
        mc = v["cells"] / 1e6
        out.append("### Targets on %s" % grid_label(g, v["cells"]))
        out.append("")
        out.append("| target | measured | met |")
        out.append("|---|---|---|")
        if p:
            r = v["wall_s"] / p["wall_s"]
            out.append("| end to end ≤ 3 × gdal_polygonize | %.1f × (CPU %.1f ×) | %s |" % (
                r, v["cpu_s"] / p["cpu_s"], "yes" if r <= 3 else "no"))
        r = peak / (inp + outp)
        out.append("| peak memory ≤ 4 × (input + output) | %.1f × (%.0f MB of %.0f MB allowed; %.1f × without "
                   "the %.0f MB program) | %s |" % (r, peak, 4 * (inp + outp), (peak - idle) / (inp + outp), idle,
                                                     "yes" if r <= 4 else "no"))
        scale = (v["wall_s"] / mc) / base_wall
        scale_cpu = (v["cpu_s"] / mc) / base_cpu
        out.append("| time per cell ≤ 1.5 × the %s one | %.2f × wall, %.2f × CPU | %s |" % (
            mirrored[0], scale, scale_cpu, "yes" if max(scale, scale_cpu) <= 1.5 else "no"))
        for name in ("pavement (C)", "blocks (D1-D5)", "road frontage (E2 input)", "spines, parcels (D6-E6)"):
            hit = [(w, c) for n, w, c, _, _ in stages[g] if n == name]
            if hit and hit[0][0] > 0:
                w, c = hit[0]
                out.append("| both cores busy in %s | %d%% CPU (200%% = both) | %s |" % (
                    name, round(100 * c / w), "yes" if c / w >= 1.8 else "no"))
        out.append("")

    text = "\n".join(out)
    print(text)
    if markdown:
        with open(markdown, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
