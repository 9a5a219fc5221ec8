#!/usr/bin/env python3
"""Performance tables: the Markdown tables of docs/performance.md from Google Benchmark JSON.

Reads the JSON output of bench_intersect and bench_frame (--benchmark_out=FILE, or stdout with
--benchmark_format=json; several files may be given, e.g. one per program) and prints:

- intersect: per model (dragon, bunny), the packet path against Embree on the same instruction
  set, one column per set raced (sse4.2, W = 4; avx2, W = 8; avx512, W = 16), 1 / 2 threads:
  packet = the best rays/s of Packet<W>, Block<W> and Stream<W> (the median-split tree), Embree
  = the best of Embree1, Embree16 and Embree1M on the same set; then packet / scalar on primary
  rays (BM_Intersect_Scalar).
- intersect-rates: per model, the best contender of each side and its Mrays/s, 1 thread.
- frame: per set, the dragon frame (BM_Frame_Scalar, BM_Frame_Packet_<set>,
  BM_Frame_PacketSah_<set>) on 1 and 2 threads, and packet / scalar.

Figures are medians of the repetitions: the "median" aggregates when the JSON has them
(--benchmark_report_aggregates_only=true), else the median of the repetitions' runs. Runs that
ended in an error are left out; a missing figure prints as "—".

Usage:
  python3 scripts/perf_tables.py intersect.json frame.json        print the tables
  python3 scripts/perf_tables.py --write docs/performance.md intersect.json frame.json
      replace each table block between <!-- tables:NAME begin --> and <!-- tables:NAME end -->
      (NAME: intersect, intersect-rates, frame) for which the JSON has figures
  python3 scripts/perf_tables.py --self-test
      runs on built-in sample JSON (both aggregate and plain repetitions) and checks the tables
      and --write against the expected text; exit status 0 when they match

scripts/bench.sh writes the JSON and runs this script (docs/performance.md, "Reproducing").
"""
import argparse
import io
import json
import math
import os
import re
import statistics
import sys
import tempfile

SETS = [("sse4.2", 4), ("avx2", 8), ("avx512", 16)]  # narrowest first, as bench/ races them
KINDS = ["primary", "shadow", "bounce"]
MISSING = "—"
BLOCKS = ["intersect", "intersect-rates", "frame"]

INTERSECT = re.compile(r"^BM_Intersect_([^/]+)/([^/]+)/(primary|shadow|bounce)/threads:(\d+)")
FRAME = re.compile(r"^BM_Frame_(Scalar|Packet|PacketSah)(?:_([^/]+))?/threads:(\d+)")


# ---- reading -----------------------------------------------------------------------------------

def to_ms(value, unit):
    return value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[unit]


def medians(documents):
    """{run name: (real time in ms, rays/s)} from parsed Google Benchmark JSON documents."""
    runs, aggregates = {}, {}
    for doc in documents:
        for b in doc.get("benchmarks", []):
            if b.get("error_occurred"):
                continue
            name = b.get("run_name", b["name"])
            rate = b.get("rays/s", b.get("items_per_second"))
            ms = to_ms(b["real_time"], b.get("time_unit", "ns"))
            if b.get("run_type") == "aggregate":
                if b.get("aggregate_name") == "median":
                    aggregates[name] = (ms, rate)
            else:
                runs.setdefault(name, []).append((ms, rate))
    out = {}
    for name, values in runs.items():
        rates = [r for _, r in values if r is not None]
        out[name] = (statistics.median(ms for ms, _ in values),
                     statistics.median(rates) if rates else None)
    out.update(aggregates)
    return out


# ---- formatting --------------------------------------------------------------------------------

def figure(value):
    """Three significant digits, trailing zeros kept: 101, 51.5, 8.58, 38.0."""
    if value is None:
        return MISSING
    digits = max(0, 2 - int(math.floor(math.log10(abs(value))))) if value else 0
    return f"{value:.{digits}f}"


def ratio(num, den):
    return None if num is None or not den else num / den


def ratio_text(value):
    return MISSING if value is None else f"{value:.2f}x"


def best(rates):
    """(name, rate) of the fastest contender that ran, or (None, None)."""
    ran = [(r, n) for n, r in rates if r is not None]
    if not ran:
        return None, None
    r, n = max(ran)
    return n, r


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|---" * len(header) + "|"]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


# ---- the tables --------------------------------------------------------------------------------

def intersect_data(m):
    """{model: {(contender, kind, threads): rays/s}}, in the order the models first appear."""
    data = {}
    for name, (_, rate) in m.items():
        g = INTERSECT.match(name)
        if g and rate is not None:
            contender, model, kind, threads = g.groups()
            data.setdefault(model, {})[(contender, kind, int(threads))] = rate
    return data


def raced_sets(runs):
    contenders = {c for c, _, _ in runs}
    return [(s, w) for s, w in SETS
            if any(c in contenders for c in (f"Packet{w}", f"Block{w}", f"Stream{w}",
                                               f"Embree16_{s}"))]


def packet_side(runs, w, kind, threads):
    return best([(c, runs.get((c, kind, threads)))
                 for c in (f"Packet{w}", f"Block{w}", f"Stream{w}")])


def embree_side(runs, s, kind, threads):
    return best([(c, runs.get((c, kind, threads)))
                 for c in (f"Embree1_{s}", f"Embree16_{s}", f"Embree1M_{s}")])


def set_label(s, w):
    return f"{s}, W = {w}"


def raced_models(m):
    """(model, its runs, the sets raced on it) of every model some set was raced on."""
    for model, runs in intersect_data(m).items():
        sets = raced_sets(runs)
        if sets:
            yield model, runs, sets


def intersect_tables(m):
    out = []
    for model, runs, sets in raced_models(m):
        rows = []
        for kind in KINDS:
            row = [kind]
            for s, w in sets:
                r = [ratio(packet_side(runs, w, kind, t)[1], embree_side(runs, s, kind, t)[1])
                     for t in (1, 2)]
                text = " / ".join(ratio_text(x) for x in r)
                row.append(f"**{text}**" if any(x is not None and x < 1 for x in r) else text)
            rows.append(row)
        row = ["packet / scalar, primary"]
        for s, w in sets:
            row.append(" / ".join(
                ratio_text(ratio(packet_side(runs, w, "primary", t)[1],
                                 runs.get(("Scalar", "primary", t)))) for t in (1, 2)))
        rows.append(row)
        out.append(table([model] + [set_label(s, w) for s, w in sets], rows))
    return "\n\n".join(out)


def intersect_rate_tables(m):
    out = []
    for model, runs, sets in raced_models(m):
        rows = []
        for kind in KINDS:
            row = [kind]
            for s, w in sets:
                name, rate = packet_side(runs, w, kind, 1)
                embree = embree_side(runs, s, kind, 1)[1]
                row.append(MISSING if name is None else
                           f"`{name}` {figure(rate * 1e-6)}; Embree "
                           f"{MISSING if embree is None else figure(embree * 1e-6)}")
            rows.append(row)
        out.append(table([f"{model}, Mrays/s, 1 thread"] + [set_label(s, w) for s, w in sets],
                         rows))
    return "\n\n".join(out)


def frame_table(m):
    ms = {}
    for name, (time, _) in m.items():
        g = FRAME.match(name)
        if g:
            path, s, threads = g.groups()
            ms[(path, s, int(threads))] = time
    if not ms:
        return ""
    sets = [(s, w) for s, w in SETS if any(k[1] == s for k in ms)]
    rows = []
    for s, w in sets:
        for t in (1, 2):
            scalar, packet = ms.get(("Scalar", None, t)), ms.get(("Packet", s, t))
            sah = ms.get(("PacketSah", s, t))
            rows.append([set_label(s, w), str(t)] +
                        [MISSING if v is None else f"{figure(v)} ms" for v in (scalar, packet, sah)]
                        + [ratio_text(ratio(scalar, packet))])
    return table(["instruction set", "threads", "scalar", "packet", "packet, SAH",
                  "packet / scalar"], rows)


def all_tables(m):
    return {"intersect": intersect_tables(m), "intersect-rates": intersect_rate_tables(m),
            "frame": frame_table(m)}


# ---- writing -----------------------------------------------------------------------------------

def replace_blocks(text, tables, log=None):
    """The text with each block that has figures replaced; raises ValueError on missing markers."""
    log = log or sys.stderr
    for name in BLOCKS:
        body = tables.get(name, "")
        begin, end = f"<!-- tables:{name} begin -->", f"<!-- tables:{name} end -->"
        if not body:
            print(f"perf_tables: no figures for {name}; its block is left as it is", file=log)
            continue
        if text.count(begin) != 1 or text.count(end) != 1 or text.index(begin) > text.index(end):
            raise ValueError(f"needs one '{begin}' ... '{end}' pair")
        head, rest = text.split(begin)
        _, tail = rest.split(end)
        text = f"{head}{begin}\n{body}\n{end}{tail}"
    return text


def main(argv, log=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("json", nargs="*", help="Google Benchmark JSON files")
    parser.add_argument("--write", metavar="MARKDOWN", help="replace the table blocks of this file")
    parser.add_argument("--self-test", action="store_true", help="check on built-in sample data")
    args = parser.parse_args(argv)
    if args.self_test:
        return self_test()
    if not args.json:
        parser.error("give one or more JSON files (or --self-test)")
    documents = []
    for path in args.json:
        with open(path, encoding="utf-8") as f:
            documents.append(json.load(f))
    tables = all_tables(medians(documents))
    if args.write:
        with open(args.write, encoding="utf-8") as f:
            text = f.read()
        try:
            text = replace_blocks(text, tables, log)
        except ValueError as e:
            print(f"perf_tables: {args.write}: {e}", file=log or sys.stderr)
            return 1
        with open(args.write, "w", encoding="utf-8") as f:
            f.write(text)
        return 0
    for name in BLOCKS:
        if tables[name]:
            print(f"<!-- tables:{name} -->\n{tables[name]}\n")
    return 0


# ---- self-test ---------------------------------------------------------------------------------

def sample_documents():
    """Two JSON documents as the benchmark programs write them: bench_intersect with median
    aggregates (two sets, one with an Embree error), bench_frame with plain repetitions."""
    context = {"date": "", "host_name": "h", "num_cpus": 2, "mhz_per_cpu": 2100,
               "library_build_type": "release"}

    def rate_run(name, rate, aggregate=None, rep=0):
        run = {"name": name + (f"_{aggregate}" if aggregate else ""), "run_name": name,
               "run_type": "aggregate" if aggregate else "iteration", "repetitions": 3,
               "threads": 1, "iterations": 10, "real_time": 1e9 / rate * 1e-6,
               "cpu_time": 1e9 / rate * 1e-6, "time_unit": "ms", "items_per_second": rate,
               "rays/s": rate}
        if aggregate:
            run["aggregate_name"] = aggregate
        else:
            run["repetition_index"] = rep
        return run

    intersect = []
    mrays = {  # contender: (primary, shadow, bounce) Mrays/s at 1 thread; 2 threads are 2x
        "Scalar": (10.0, 2.0, 0.5),
        "Packet4": (40.0, 8.0, 2.73), "Block4": (51.5, 8.58, 2.5), "Stream4": (30.0, 7.0, 2.0),
        "Block4Sah": (99.0, 99.0, 99.0),  # SAH contenders are not the packet figure
        "Embree1_sse4.2": (20.0, 5.0, 4.75), "Embree16_sse4.2": (49.0, 8.47, 3.0),
        "Embree1M_sse4.2": (30.0, None, 4.0),
        "Packet16": (90.0, 15.0, 7.0), "Block16": (101.0, 16.6, 6.0),
        "Stream16": (80.0, 14.0, 8.23),
        "Embree1_avx512": (40.0, 10.0, 5.99), "Embree16_avx512": (80.4, 21.7, 5.0),
        "Embree1M_avx512": (50.0, None, 5.5),
    }
    for contender, rates in mrays.items():
        for kind, rate in zip(KINDS, rates):
            if rate is None:
                continue
            for threads in (1, 2):
                name = f"BM_Intersect_{contender}/dragon/{kind}/threads:{threads}/real_time"
                r = rate * 1e6 * threads
                intersect += [rate_run(name, r * f, rep=i) for i, f in enumerate((0.9, 1.0, 1.2))]
                intersect += [rate_run(name, r * 1.1, "mean"), rate_run(name, r, "median")]
    intersect.append({"name": "BM_Intersect_Embree16_avx512/dragon/bounce/threads:1/real_time",
                      "run_name": "BM_Intersect_Embree16_avx512/dragon/bounce/threads:1/real_time",
                      "run_type": "iteration", "error_occurred": True,
                      "error_message": "x", "real_time": 0, "time_unit": "ms"})
    frame = []
    times = {"Scalar": (598.0, 352.0), "Packet_avx512": (70.2, 38.0),
             "PacketSah_avx512": (62.6, 30.9), "Packet_avx2": (80.0, 40.0)}
    for path, (one, two) in times.items():
        for threads, t in ((1, one), (2, two)):
            name = f"BM_Frame_{path}/threads:{threads}/real_time"
            for i, f in enumerate((1.0, 0.95, 1.3)):  # the median is the first
                frame.append({"name": name, "run_name": name, "run_type": "iteration",
                              "repetition_index": i, "repetitions": 3, "threads": 1,
                              "iterations": 1, "real_time": t * f * 1e6, "cpu_time": t * 1e6,
                              "time_unit": "ns", "rays/s": 4.7e6 / (t * f * 1e-3)})
    return [{"context": context, "benchmarks": intersect}, {"context": context,
                                                             "benchmarks": frame}]


EXPECTED = {
    "intersect": """\
| dragon | sse4.2, W = 4 | avx512, W = 16 |
|---|---|---|
| primary | 1.05x / 1.05x | 1.26x / 1.26x |
| shadow | 1.01x / 1.01x | **0.76x / 0.76x** |
| bounce | **0.57x / 0.57x** | 1.37x / 1.37x |
| packet / scalar, primary | 5.15x / 5.15x | 10.10x / 10.10x |""",
    "intersect-rates": """\
| dragon, Mrays/s, 1 thread | sse4.2, W = 4 | avx512, W = 16 |
|---|---|---|
| primary | `Block4` 51.5; Embree 49.0 | `Block16` 101; Embree 80.4 |
| shadow | `Block4` 8.58; Embree 8.47 | `Block16` 16.6; Embree 21.7 |
| bounce | `Packet4` 2.73; Embree 4.75 | `Stream16` 8.23; Embree 5.99 |""",
    "frame": """\
| instruction set | threads | scalar | packet | packet, SAH | packet / scalar |
|---|---|---|---|---|---|
| avx2, W = 8 | 1 | 598 ms | 80.0 ms | — | 7.47x |
| avx2, W = 8 | 2 | 352 ms | 40.0 ms | — | 8.80x |
| avx512, W = 16 | 1 | 598 ms | 70.2 ms | 62.6 ms | 8.52x |
| avx512, W = 16 | 2 | 352 ms | 38.0 ms | 30.9 ms | 9.26x |""",
}


def self_test():
    failures = []
    quiet = io.StringIO()  # the messages the failing cases print on purpose
    m = medians(sample_documents())
    got = all_tables(m)
    for name in BLOCKS:
        if got[name] != EXPECTED[name]:
            failures.append(f"{name}: expected\n{EXPECTED[name]}\ngot\n{got[name]}")
    # --write through files: both blocks replaced, the text around them kept, a block without
    # figures left alone, a missing marker refused
    doc = ("# Page\nbefore\n<!-- tables:intersect begin -->\nold\n<!-- tables:intersect end -->\n"
           "middle\n<!-- tables:intersect-rates begin -->\n<!-- tables:intersect-rates end -->\n"
           "<!-- tables:frame begin -->\nold frame\n<!-- tables:frame end -->\nafter\n")
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i, d in enumerate(sample_documents()):
            paths.append(os.path.join(tmp, f"{i}.json"))
            with open(paths[-1], "w", encoding="utf-8") as f:
                json.dump(d, f)
        page = os.path.join(tmp, "page.md")
        with open(page, "w", encoding="utf-8") as f:
            f.write(doc)
        status = main(["--write", page] + paths, quiet)
        with open(page, encoding="utf-8") as f:
            written = f.read()
        want = (f"# Page\nbefore\n<!-- tables:intersect begin -->\n{EXPECTED['intersect']}\n"
                f"<!-- tables:intersect end -->\nmiddle\n<!-- tables:intersect-rates begin -->\n"
                f"{EXPECTED['intersect-rates']}\n<!-- tables:intersect-rates end -->\n"
                f"<!-- tables:frame begin -->\n{EXPECTED['frame']}\n<!-- tables:frame end -->\n"
                f"after\n")
        if status != 0 or written != want:
            failures.append(f"--write: status {status}, wrote\n{written}")
        with open(page, "w", encoding="utf-8") as f:
            f.write(doc)
        status = main(["--write", page, paths[0]], quiet)  # intersect only: the frame block stays
        with open(page, encoding="utf-8") as f:
            if status != 0 or "old frame" not in f.read():
                failures.append("--write with intersect figures only changed the frame block")
        with open(page, "w", encoding="utf-8") as f:
            f.write(doc.replace("<!-- tables:frame end -->", ""))
        if main(["--write", page] + paths, quiet) != 1:
            failures.append("--write accepted a block without its end marker")
    for f in failures:
        print(f"perf_tables self-test: {f}", file=sys.stderr)
    print("perf_tables self-test: " + ("failed" if failures else "ok"), file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
