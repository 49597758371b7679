"""`urbanvec-tiles`: run `urbanvec vectorize` as tiles (sequentially, on a local Dask cluster or on a
Dask scheduler) and stitch them into one GeoPackage; `digest` and `compare` check two outputs for
equality (docs/scale.md)."""
import json
import os
import pickle
import shutil
import socket
import subprocess
import sys
import time

from osgeo import gdal

from urbanvec_tiles import digest as D
from urbanvec_tiles import geom as G
from urbanvec_tiles import plan as P
from urbanvec_tiles import regions as R
from urbanvec_tiles import stitch as S
from urbanvec_tiles import tile as T

gdal.UseExceptions()

USAGE = """Usage: urbanvec-tiles run [--local N | --scheduler ADDRESS | --sequential] -tile CELLS -halo CELLS
                          [-max-halo CELLS] [--workdir DIR] [--keep-tiles] [--retries N]
                          [--connect-timeout SECONDS] [-overwrite] [-q] [-progress lines]
                          [vectorize options] <landuse.tif> <output.gpkg>
       urbanvec-tiles digest <city.gpkg>
       urbanvec-tiles compare <a.gpkg> <b.gpkg>

Runs `urbanvec vectorize` on core tiles of CELLS x CELLS cells, each read with a halo of CELLS around it
(-srcwin), one task per tile on Dask distributed (--local N: a local cluster of N worker processes,
default the number of cores; --scheduler: an existing cluster whose workers see the same folders;
--sequential: no Dask), and stitches the tiles into one GeoPackage, written under a temporary name and
renamed when complete. A block (with its parcels and spines) belongs to the tile whose core holds its
representative point; roads, pavement and water are cut at the core edges and joined again. A kept
block that reaches a cut edge of its window makes the tile run again with twice the halo, up to
-max-halo (default 4 x -halo), else the run fails naming the tile. Vectorize options (-density,
-parcels, -seed, -tries ...) are passed to every tile. See docs/scale.md.

digest prints a canonical digest per layer (ids left out, links followed, geometry normalized and
rounded to 1 mm, features sorted); compare matches the features of two outputs and reports the
largest coordinate difference (exit 1 when they differ by more than 1e-6 m).
"""

DRIVER_OPTS = {"--local": 1, "--scheduler": 1, "--sequential": 0, "-tile": 1, "-halo": 1, "-max-halo": 1,
               "--workdir": 1, "--keep-tiles": 0, "--retries": 1, "--connect-timeout": 1,
               "-overwrite": 0, "-q": 0, "-progress": 1, "--urbanvec": 1}
REFUSED = {"-srcwin": "the driver sets each tile's window",
           "-open-regions": "the driver computes it for the whole grid", "-of": "the stitched output is a GeoPackage",
           "-lco": "not supported by the stitcher", "-dsco": "not supported by the stitcher",
           "-debug-stages": "use it on a single run", "-timings": "use it on a single run"}


class Failure(Exception):
    def __init__(self, message, code=1):
        super().__init__(message)
        self.code = code


def find_urbanvec(explicit):
    if explicit:
        return explicit
    env = os.environ.get("URBANVEC")
    if env:
        return env
    here = os.path.dirname(os.path.realpath(sys.argv[0]))
    for cand in (os.path.join(here, "urbanvec"), os.path.join(here, "..", "build", "bin", "urbanvec")):
        if os.path.isfile(cand) and os.access(cand, os.X_OK):
            return os.path.abspath(cand)
    found = shutil.which("urbanvec")
    if not found:
        raise Failure("cannot find the urbanvec program (give --urbanvec PATH or set URBANVEC)")
    return found


def parse_run(argv):
    opts, vargs, positionals = {}, [], []
    i = 0
    usage = None
    while i < len(argv):
        a = argv[i]
        if a in DRIVER_OPTS:
            n = DRIVER_OPTS[a]
            if i + n >= len(argv):
                raise Failure("option %s needs a value" % a, 2)
            opts[a] = argv[i + 1] if n else True
            i += 1 + n
            continue
        if a.startswith("-") and len(a) > 1:
            if a in REFUSED:
                raise Failure("option %s is not taken by urbanvec-tiles run: %s" % (a, REFUSED[a]), 2)
            if usage is None:
                usage = vectorize_usage(find_urbanvec(opts.get("--urbanvec")))
            spec = usage.get(a)
            if spec is None:
                raise Failure("unknown option '%s' (see urbanvec-tiles --help and urbanvec vectorize --help)" % a, 2)
            arity, role = spec
            if i + arity >= len(argv):
                raise Failure("option %s needs %d value%s" % (a, arity, "s" if arity > 1 else ""), 2)
            vals = argv[i + 1:i + 1 + arity]
            if role in ("input_raster", "input_file"):
                vals = [os.path.abspath(v) for v in vals]
            vargs += [a] + vals
            i += 1 + arity
            continue
        positionals.append(a)
        i += 1
    if len(positionals) != 2:
        raise Failure("'urbanvec-tiles run' expects <landuse> <output>, got %d arguments" % len(positionals), 2)
    return opts, vargs, positionals


def vectorize_usage(urbanvec):
    out = subprocess.run([urbanvec, "vectorize", "--json-usage"], stdout=subprocess.PIPE, text=True,
                         check=True).stdout
    return {o["name"]: (o.get("arity", 1), o.get("role", "")) for o in json.loads(out)["options"]}


def integer(opts, name, default=None):
    if name not in opts:
        if default is None:
            raise Failure("option %s is required" % name, 2)
        return default
    try:
        return int(opts[name])
    except ValueError:
        raise Failure("option %s takes a whole number of cells, got '%s'" % (name, opts[name]), 2)


class Progress:
    """GDAL-style 0...10...100 - done. on stdout, or PROGRESS lines, over tiles."""

    def __init__(self, quiet, lines):
        self.quiet, self.lines, self.printed = quiet, lines, -1

    def __call__(self, fraction, stage):
        if self.quiet:
            return
        pct = int(fraction * 100 + 1e-9)
        if self.lines:
            print("PROGRESS %d %s" % (pct, stage), flush=True)
            return
        step = pct // 2 * 2
        for p in range(self.printed + 2 if self.printed >= 0 else 0, step + 1, 2):
            sys.stdout.write(("%d" % p) if p % 10 == 0 else ".")
            if p == 100:
                sys.stdout.write(" - done.\n")
        self.printed = max(self.printed, step)
        sys.stdout.flush()


def check_scheduler(address, timeout):
    """A clear error within `timeout` seconds when nothing answers at the scheduler's address."""
    hostport = address.split("://", 1)[-1]
    host, _, port = hostport.rpartition(":")
    try:
        with socket.create_connection((host or "localhost", int(port)), timeout=timeout):
            pass
    except (OSError, ValueError) as e:
        raise Failure("scheduler '%s' does not answer (%s); start it (dask scheduler) or check the "
                      "address" % (address, e.strerror or e))


def run(argv):
    opts, vargs, (landuse, output) = parse_run(argv)
    # Stage B7 (through roads and straight roads) runs in the tiles as in a single run: it decides per
    # chain between intersections, and the halo guard redoes a tile whose kept road line (a chain) runs
    # out of its window (docs/scale.md, "Stage B7 in tiles"). `-no-through-roads` is passed on like any
    # vectorize option.
    quiet = bool(opts.get("-q"))
    progress = Progress(quiet, opts.get("-progress") == "lines")
    tile_cells = integer(opts, "-tile")
    halo = integer(opts, "-halo")
    retries = integer(opts, "--retries", 2)
    timeout = float(opts.get("--connect-timeout", 10))
    modes = [m for m in ("--local", "--scheduler", "--sequential") if m in opts]
    if len(modes) > 1:
        raise Failure("give one of --local, --scheduler and --sequential, not %s" % " and ".join(modes), 2)
    urbanvec = find_urbanvec(opts.get("--urbanvec"))
    landuse = os.path.abspath(landuse)
    output = os.path.abspath(output)
    if not output.lower().endswith(".gpkg"):
        raise Failure("the output '%s' must be a GeoPackage (.gpkg)" % output, 2)
    try:
        ds = gdal.Open(landuse)
    except RuntimeError as e:
        raise Failure("land-use raster '%s' cannot be read (%s)" % (landuse, str(e).strip()))
    width, height = ds.RasterXSize, ds.RasterYSize
    crs_wkt = ds.GetProjection()
    try:
        frame = G.Frame(ds.GetGeoTransform(), width, height)
    except ValueError as e:
        raise Failure("land-use raster '%s': %s" % (landuse, e))
    ds = None
    try:
        tiles = P.plan(width, height, tile_cells, halo)
    except P.UsageError as e:
        raise Failure(str(e), 2)
    max_halo = integer(opts, "-max-halo", max(4 * halo, 1))
    if max_halo < halo:
        raise Failure("-max-halo %d is smaller than -halo %d" % (max_halo, halo), 2)
    if os.path.exists(output) and not opts.get("-overwrite"):
        raise Failure("output file '%s' exists; give -overwrite to replace it" % output)
    if os.path.exists(output) and os.path.samefile(output, landuse):
        raise Failure("output file '%s' would replace the input '%s'" % (output, landuse))
    outdir = os.path.dirname(output)
    if not os.path.isdir(outdir) or not os.access(outdir, os.W_OK):
        raise Failure("the output folder '%s' does not exist or is not writable" % outdir)
    if modes and modes[0] == "--scheduler":
        check_scheduler(opts["--scheduler"], timeout)

    base = os.path.basename(output)
    workdir = os.path.abspath(opts.get("--workdir") or os.path.join(outdir, ".%s.tiles-%d" % (base, os.getpid())))
    own_workdir = not os.path.exists(workdir)
    os.makedirs(workdir, exist_ok=True)
    tmp = os.path.join(outdir, ".%s.tmp-%d.gpkg" % (base[:-5], os.getpid()))
    roads_only = "-roads-only" in vargs
    classes = vargs[vargs.index("-classes") + 1] if "-classes" in vargs else None
    started = time.time()
    try:
        # The whole grid's road-bounded regions (regions.py): which are open land, and the extent of
        # each enclosed one, so a tile classes the regions it cuts as a single run does and reads
        # every enclosed region its core meets whole.
        open_path = os.path.join(workdir, "open_regions.tif")
        regions = R.compute(landuse, classes, tiles, tile_cells, frame, open_path, progress)
        tile_vargs = vargs + ["-open-regions", open_path]
        jobs = [{"tile": t, "frame": frame, "halo": halo, "max_halo": max_halo, "workdir": workdir,
                 "urbanvec": urbanvec, "vargs": tile_vargs, "landuse": landuse, "roads_only": roads_only,
                 "keep_tiles": bool(opts.get("--keep-tiles")), "classes": classes,
                 "open_regions": open_path, "boxes": regions.enclosed_boxes(t)} for t in tiles]
        results = execute(jobs, modes[0] if modes else "--local", opts, retries, timeout, progress)
        parts = []
        for r in results:
            with open(r["owned"], "rb") as fh:
                parts.append(pickle.load(fh))
        styles = styles_of(jobs, results)
        layers = T.ROADS_ONLY_LAYERS if roads_only else T.LAYERS
        progress(0.95, "stitching")
        gdal.SetConfigOption("OGR_CURRENT_DATE", os.environ.get("OGR_CURRENT_DATE", "2026-01-01T00:00:00.000Z"))
        counts, warnings = S.stitch(parts, frame, tile_cells, layers, crs_wkt, styles, tmp)
        os.replace(tmp, output)
        progress(1.0, "done")
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
        if own_workdir and not opts.get("--keep-tiles"):
            shutil.rmtree(workdir, ignore_errors=True)
    redone = [r for r in results if len(r["attempts"]) > 1]
    for w in warnings:
        print("Warning: " + w, file=sys.stderr)
    if not quiet:
        print("%d tiles (%d redone with a larger halo) in %.1f s: %s" % (
            len(results), len(redone), time.time() - started,
            ", ".join("%d %s" % (counts[k], k) for k in layers)))
    return 0


def styles_of(jobs, results):
    """The layer_styles table of the tiles (the same in every tile): read from one tile's summary."""
    for r in results:
        if r.get("styles"):
            return r["styles"]
    return None


def execute(jobs, mode, opts, retries, timeout, progress):
    n = len(jobs)
    progress(0.1, "tiles")  # 0..0.1: the regions pass (regions.py)
    if mode == "--sequential":
        out = []
        for k, job in enumerate(jobs):
            out.append(T.run_tile(job))
            progress(0.1 + 0.85 * (k + 1) / n, "tiles")
        return out
    import logging

    from distributed import Client, LocalCluster, as_completed

    logging.getLogger("distributed").setLevel(logging.ERROR)
    cluster = None
    try:
        if mode == "--scheduler":
            try:
                client = Client(opts["--scheduler"], timeout=timeout)
            except (OSError, TimeoutError) as e:
                raise Failure("scheduler '%s' does not answer within %g s (%s)" % (opts["--scheduler"], timeout, e))
        else:
            workers = int(opts.get("--local", os.cpu_count() or 1))
            if workers < 1:
                raise Failure("--local takes a number of workers >= 1, got %d" % workers, 2)
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR)
            client = Client(cluster)
        futures = [client.submit(T.run_tile, job, key="urbanvec-tile-%s" % job["tile"].name, retries=retries,
                                 pure=False) for job in jobs]
        done = {}
        for k, fut in enumerate(as_completed(futures), start=1):
            try:
                r = fut.result()
            except T.TileError as e:
                raise Failure(str(e))
            except Exception as e:  # a task that failed on every try, or a lost worker
                raise Failure("tile task %s failed: %s" % (fut.key, e))
            done[r["tile"]] = r
            progress(0.1 + 0.85 * k / n, "tiles")
        client.close()
        return [done[j["tile"].name] for j in jobs]
    finally:
        if cluster is not None:
            cluster.close()


def main(argv):
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(USAGE)
        return 0 if argv else 2
    cmd, rest = argv[0], argv[1:]
    try:
        if cmd == "run":
            if "--help" in rest:
                print(USAGE)
                return 0
            return run(rest)
        if cmd == "digest":
            if len(rest) != 1:
                raise Failure("'urbanvec-tiles digest' expects <city.gpkg>", 2)
            for layer, h, n in D.digest(rest[0]):
                print("%s %s %d" % (layer, h, n))
            return 0
        if cmd == "compare":
            if len(rest) != 2:
                raise Failure("'urbanvec-tiles compare' expects <a.gpkg> <b.gpkg>", 2)
            ok, lines = D.compare(rest[0], rest[1])
            for l in lines:
                print(l)
            return 0 if ok else 1
        raise Failure("unknown subcommand '%s' (run, digest, compare)" % cmd, 2)
    except Failure as e:
        print("ERROR: %s" % e, file=sys.stderr)
        return e.code
    except T.TileError as e:
        print("ERROR: %s" % e, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("ERROR: cancelled; no output was written", file=sys.stderr)
        return 3
