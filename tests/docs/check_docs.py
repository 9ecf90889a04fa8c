#!/usr/bin/python3
"""The docs test: README.md and every page of docs/ hold true for a newcomer
who follows them literally (ctest label docs; README.md's list of the docs
points here).

  check_docs.py pages    --source DIR --build DIR [--pending FILE]
  check_docs.py commands --source DIR --build DIR [--long]

`pages` reads every page with markdown-it (Debian's python3-markdown-it) and
checks, without running anything but the programs' --help:
  - every relative link and image resolves to a file of the repository, and
    every #anchor to a heading or an <a id> of the page it points to; a
    section named in quotes after its page (model.md, "Effects") is there;
  - every repository path the text names (libball/scenes/x.yaml,
    tests/unit/test_x.c, ball/scene.h, build/libball/ballsim, a bare
    tennis.yaml or test_x.c) exists;
  - every identifier in a code span that names code (ball_step, BALL_OK,
    floor_bounce, a ctest name) is a word of the sources or a ctest test, and
    a constant given with its value (`BALL_MAX_WALLS` (16)) has that value;
  - every option of one of the project's programs (ballsim --fps, a
    ball-server option, a ./run verb) is in that program's --help, or in
    ./run's usage.
`commands` runs the code blocks marked runnable (the line before the fence):
  <!-- runnable -->          each line is a command that must exit 0; in a
                             block whose lines start with "$ ", what follows
                             a command up to the next "$ " is its output,
                             which must be what it prints (stdout + stderr)
  <!-- runnable: errors -->  the same, but every command must fail (an
                             example error message and the input making it)
  <!-- runnable: long -->    runs only with --long (`./run docs-long`), else
                             is reported as left to it
Commands run in a scratch folder that links every top-level entry of the
source tree and `build` to the build tree, so that `build/libball/ballsim
libball/scenes/x.yaml --out x.csv` works as written and writes nowhere in
the source tree; BALL_BUILD_DIR is the build tree (so `./run VERB` uses it).
A `./run` command runs in the source tree itself (./run configures the build
with the tree it lives in), so it must write outside it (--out /tmp/x.csv).
A ctest command is listed (--show-only), not run, and must find tests. A
command that starts ball-server, ball-bot, ball-watch or ball-load must carry
--domain N (the DDS tests use fixed domains of their own), and a DDS command
(those, ./run demo, ./run bench-server) belongs in a long block, which runs
only under `./run docs-long` (on the demo's and the benchmark's own domains,
never in the test suite beside the DDS tests).

Either mode fails when it checks nothing: no page, no code block, no link,
no runnable command. A failure listed in --pending (one line each, as this
test prints it but without the line number) is reported as pending instead;
a pending line that no longer fails is itself a failure, so the list only
shrinks.
"""

import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

from markdown_it import MarkdownIt

PROGRAMS = {  # program -> where the build puts it
    "ballsim": "libball/ballsim",
    "ballrender": "libball/ballrender",
    "ball-server": "server/ball-server",
    "ball-bot": "server/ball-bot",
    "ball-watch": "server/ball-watch",
    "ball-load": "server/ball-load",
    "ball-demo": "server/ball-demo",
    "ball_validate": "validation/ball_validate",
    "ball_bench": "tests/bench/ball_bench",
    "ball_bench_libm": "tests/bench/ball_bench_libm",
    "ball_bench_mujoco": "validation/ball_bench_mujoco",
    "ball_accuracy": "validation/ball_accuracy",
}
# identifiers a page may name from the libraries the project uses
EXTERNAL_HEADERS = ("/usr/include/mujoco", "/usr/include/fcl")
RUN_VERB_PROGRAMS = {  # ./run VERB ARGS hands ARGS to
    "ballsim": "ballsim", "demo": "ball-demo", "bench": "ball_bench", "bench-server": "ball-load",
    "validate-full": "ball_validate", "accuracy": "ball_accuracy",
}
DDS_PROGRAMS = ("ball-server", "ball-bot", "ball-watch", "ball-load")
CODE_EXTENSIONS = (".c", ".h", ".cpp", ".cmake", ".idl", ".xml", ".gp", ".supp", ".yaml")
MARKER = re.compile(r"^<!--\s*runnable(?::\s*(errors|long))?\s*-->\s*$")


def pages_of(source, only=None):
    if only:
        return only
    pages = ["README.md"] + sorted(os.path.relpath(p, source)
                                   for p in glob.glob(os.path.join(source, "docs", "*.md")))
    return [p for p in pages if os.path.isfile(os.path.join(source, p))]


def parse(source, page):
    with open(os.path.join(source, page), encoding="utf-8") as f:
        text = f.read()
    md = MarkdownIt("commonmark").enable("table")
    return text, md.parse(text)


def slug(title):
    """GitHub's heading anchor: lower case, punctuation dropped, spaces to -."""
    s = title.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def inline_text(token):
    return "".join(c.content for c in (token.children or []) if c.type in ("text", "code_inline"))


def anchors_of(tokens):
    found, seen = set(), {}
    for i, t in enumerate(tokens):
        if t.type == "heading_open":
            base = slug(inline_text(tokens[i + 1]))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else "%s-%d" % (base, n))
        if t.type in ("html_block", "inline"):
            for c in [t] + list(t.children or []):
                if c.type in ("html_block", "html_inline"):
                    found.update(re.findall(r'<a\s+(?:id|name)="([^"]+)"', c.content))
    return found


def walk_inline(tokens):
    for t in tokens:
        if t.type == "inline":
            for c in t.children or []:
                yield c


class Report:
    def __init__(self, pending_file):
        self.failures, self.notes, self.counts = [], [], {}
        self.pending = []
        if pending_file and os.path.isfile(pending_file):
            with open(pending_file, encoding="utf-8") as f:
                self.pending = [l.rstrip("\n") for l in f
                                if l.strip() and not l.startswith("#")]

    def count(self, what, n=1):
        self.counts[what] = self.counts.get(what, 0) + n

    def fail(self, page, line, what):
        self.failures.append("%s:%s: %s" % (page, line, what))

    def finish(self, needed):
        ok = True
        for what in needed:
            if self.counts.get(what, 0) == 0:
                print("FAIL: checked no %s: the test would pass on nothing" % what)
                ok = False
        pending_seen = set()
        for f in self.failures:
            key = re.sub(r"^([^:]+):[0-9?]+:", r"\1:", f)  # pending lines name no line
            if key in self.pending:
                pending_seen.add(key)
                print("PENDING " + f)
            else:
                print("FAIL " + f)
                ok = False
        for p in self.pending:
            if p not in pending_seen:
                print("FAIL pending line no longer fails (remove it from the list): " + p)
                ok = False
        for n in self.notes:
            print(n)
        print("checked: " + ", ".join("%d %s" % (v, k) for k, v in sorted(self.counts.items())))
        print("docs: " + ("ok" if ok else "FAILED"))
        return 0 if ok else 1


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


# ---------------------------------------------------------------- pages mode

def repo_files(source):
    out = subprocess.run(["git", "-C", source, "ls-files"], capture_output=True, text=True)
    files = out.stdout.split()
    if out.returncode != 0 or not files:  # not a git checkout: walk the tree
        files = []
        for root, dirs, names in os.walk(source):
            dirs[:] = [d for d in dirs if not d.startswith(("build", "."))]
            files += [os.path.relpath(os.path.join(root, n), source) for n in names]
    return files


def help_texts(build, source):
    texts = {}
    for prog, rel in PROGRAMS.items():
        path = os.path.join(build, rel)
        if os.path.exists(path):
            r = subprocess.run([path, "--help"], capture_output=True, text=True, timeout=30)
            texts[prog] = r.stdout + r.stderr
    r = subprocess.run([os.path.join(source, "run"), "help"], capture_output=True, text=True,
                       timeout=30)
    texts["./run"] = r.stdout + r.stderr
    return texts


def ctest_names(build):
    r = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"],
                       capture_output=True, text=True, timeout=60)
    names = set(re.findall(r'"name"\s*:\s*"([^"]+)"', r.stdout))
    return names


def source_words(source, files):
    words = set()
    for f in files:
        if f.startswith("tests/docs/"):
            continue  # this test's own files (the pending list) name nothing
        if f.endswith((".c", ".h", ".cpp", ".cmake", ".txt", ".idl", ".xml", ".py", ".gp")) \
                or os.path.basename(f) in ("run",):
            try:
                with open(os.path.join(source, f), encoding="utf-8", errors="replace") as fh:
                    words.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", fh.read()))
            except OSError:
                pass
    for d in EXTERNAL_HEADERS:
        for root, _, names in os.walk(d):
            for n in names:
                with open(os.path.join(root, n), encoding="utf-8", errors="replace") as fh:
                    words.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", fh.read()))
    words.update(os.path.splitext(os.path.basename(f))[0] for f in files)
    return words


def command_words(line):
    """A command line as words, or None; env assignments dropped."""
    try:
        words = shlex.split(line, comments=True)
    except ValueError:
        return None
    while words and re.match(r"^[A-Z_][A-Z0-9_]*=", words[0]):
        words = words[1:]
    if words and words[0] in ("flock",) and len(words) > 2:
        words = words[2:]
    return words or None


def program_of(word):
    if word in ("./run", "run"):
        return "./run"
    base = os.path.basename(word)
    if base in PROGRAMS and (word == base or word.startswith(("build/", "./build/"))):
        return base
    return None


def options_of(words):
    return [w.split("=", 1)[0] for w in words if re.match(r"^--[a-z][a-z0-9-]*", w)]


def has_option(help_text, opt):
    return re.search(r"(?<![\w-])" + re.escape(opt) + r"(?![\w-])", help_text) is not None


def run_verbs(help_text):
    m = re.search(r"^verbs:(.*?)^\S", help_text + "\nend", re.S | re.M)
    return set(re.findall(r"^  ([a-z][a-z-]*)\b", m.group(1) if m else "", re.M))


def check_command(report, page, line, words, helps):
    prog = program_of(words[0])
    if prog is None:
        return
    report.count("program commands")
    opts = options_of(words[1:])
    if prog == "./run":
        verbs = run_verbs(helps.get("./run", ""))
        verb = words[1] if len(words) > 1 else None
        if verb is not None and not verb.startswith("-"):
            if verb not in verbs:
                report.fail(page, line, "`./run %s`: no such verb in ./run's usage" % verb)
                return
            prog = RUN_VERB_PROGRAMS.get(verb)
            if prog is None:
                return
            opts = options_of(words[2:])
        else:
            return
    text = helps.get(prog)
    if text is None:
        report.fail(page, line, "%s: not built, cannot read its --help" % prog)
        return
    for opt in opts:
        report.count("options")
        if not has_option(text, opt):
            report.fail(page, line, "`%s %s`: not in %s --help" % (prog, opt, prog))


PATH_TOKEN = re.compile(r"(?<![\w./<>$@:-])((?:\.\./)?[A-Za-z_][\w.-]*(?:/[\w.*-]+)+/?)")
BARE_FILE = re.compile(r"(?<![\w./-])([A-Za-z_][\w-]*\.(?:c|h|cpp|cmake|idl|xml|gp|supp|yaml))(?![\w/-])")
IDENT = re.compile(r"^(?:ball_\w+|ball__\w+|BALL_[A-Z0-9_]+|[a-z][a-z0-9]*(?:_[a-z0-9]+)+)(?:\(\))?$")


def exists_path(source, build, files, dirs, path):
    p = path.rstrip("/")
    if p.startswith("build/"):
        return os.path.exists(os.path.join(build, p[len("build/"):]))
    for root in ("", "libball/include/", "server/net/include/"):  # (ball/x.h: the installed headers)
        cand = root + p
        if any(ch in cand for ch in "*?["):
            if glob.glob(os.path.join(source, cand)):
                return True
        elif cand in files or cand in dirs:
            return True
    return False


def tree_parents(text, tokens):
    """In a code block drawn as a folder tree (entries indented under their
    folder), line number -> the folder path its first word is under."""
    parents = {}
    lines = text.splitlines()
    for t in tokens:
        if t.type != "fence" or not t.map:
            continue
        stack = []  # (indent, path)
        for n in range(t.map[0] + 1, t.map[1] - 1):
            raw = lines[n]
            m = re.match(r"^( *)(\S+)", raw)
            if not m:
                continue
            indent, word = len(m.group(1)), m.group(2)
            while stack and stack[-1][0] >= indent:
                stack.pop()
            if stack:
                parents[n + 1] = stack[-1][1]
            if word.endswith("/"):
                stack.append((indent, (stack[-1][1] if stack else "") + word))
    return parents


def check_pages(args):
    report = Report(args.pending)
    source, build = args.source, args.build
    files = repo_files(source)
    fileset = set(files)
    dirs = set()
    for f in files:
        parts = f.split("/")
        for i in range(1, len(parts)):
            dirs.add("/".join(parts[:i]))
    dir_names = {d.split("/")[-1] for d in dirs} | {d.split("/")[0] for d in dirs}
    basenames = {os.path.basename(f) for f in files}
    helps = help_texts(build, source)
    tests = ctest_names(build)
    words = source_words(source, files)
    defines = {}
    for f in files:
        if f.startswith("libball/") and f.endswith((".h", ".c")):
            with open(os.path.join(source, f), encoding="utf-8", errors="replace") as fh:
                for name, value in re.findall(r"^#define (BALL_\w+) \(?([0-9][0-9.e+-]*)", fh.read(), re.M):
                    defines[name] = value
    pages = pages_of(source, args.pages)
    parsed = {p: parse(source, p) for p in pages}
    anchors = {p: anchors_of(toks) for p, (_, toks) in parsed.items()}
    for page in pages:
        report.count("pages")
        text, tokens = parsed[page]
        here = os.path.dirname(page)
        # links and images
        for t in tokens:
            for c in [t] + list(t.children or []):
                target = None
                if c.type == "link_open":
                    target = c.attrs.get("href")
                elif c.type == "image":
                    target = c.attrs.get("src")
                if not target or re.match(r"^[a-z]+:", target):
                    continue
                report.count("links")
                line = (t.map[0] + 1) if t.map else "?"
                path, _, frag = target.partition("#")
                dest = os.path.normpath(os.path.join(here, path)) if path else page
                if path and dest not in fileset and dest not in dirs:
                    report.fail(page, line, "link %s: no file %s" % (target, dest))
                    continue
                if frag:
                    if dest not in anchors:
                        if dest.endswith(".md"):
                            anchors[dest] = anchors_of(parse(source, dest)[1])
                        else:
                            report.fail(page, line, "link %s: an anchor into a non-page" % target)
                            continue
                    if frag not in anchors[dest]:
                        report.fail(page, line, "link %s: no heading or anchor #%s in %s"
                                    % (target, frag, dest))
        # a section named in quotes after its page: [x.md](x.md#a), "Name" or x.md, "Name"
        for m in re.finditer(r'(?:\]\(([\w./-]+\.md)(?:#[\w-]*)?\)|(?<![\w/.-])([\w./-]+\.md))'
                             r',?\s+"([^"]+)"', text):
            target = m.group(1) or m.group(2)
            dest = os.path.normpath(os.path.join(here, target)) if m.group(1) else target
            if dest not in fileset:
                for cand in (os.path.normpath(os.path.join(here, target)), "docs/" + target):
                    if cand in fileset:
                        dest = cand
            if dest not in fileset:
                continue  # the path check reports it
            report.count("section names")
            with open(os.path.join(source, dest), encoding="utf-8") as fh:
                body = " ".join(fh.read().replace("**", "").split())
            if " ".join(m.group(3).split()) not in body:
                report.fail(page, line_of(text, m.start()), '%s, "%s": no such section in %s'
                            % (target, " ".join(m.group(3).split()), dest))
        # code blocks: count, and read their command lines
        for t in tokens:
            if t.type == "fence" or t.type == "code_block":
                report.count("code blocks")
                if t.info.strip() in ("", "sh", "bash", "shell", "console"):
                    for k, raw in enumerate(t.content.splitlines()):
                        cmd = raw[2:] if raw.startswith("$ ") else raw
                        for part in re.split(r"\s*(?:&&|\|\||;|\|)\s*", cmd):
                            w = command_words(part)
                            if w:
                                check_command(report, page, t.map[0] + 2 + k, w, helps)
        # code spans: commands, bare options, identifiers
        page_programs = set()
        for m in re.finditer(r"(?<![\w-])(%s|\./run)(?![\w-])"
                             % "|".join(re.escape(p) for p in PROGRAMS), text):
            page_programs.add(m.group(1))
        for t in tokens:
            if t.type != "inline":
                continue
            line = t.map[0] + 1 if t.map else "?"
            for c in t.children or []:
                if c.type != "code_inline":
                    continue
                span = c.content.strip()
                w = command_words(span)
                if w and program_of(w[0]):
                    check_command(report, page, line, w, helps)
                elif w and re.match(r"^--[a-z][\w-]*", w[0]) and w[0].split("=")[0] != "--opt":
                    opt = w[0].split("=", 1)[0]
                    progs = [p for p in page_programs if p in helps or p == "./run"]
                    if progs:
                        report.count("options")
                        if not any(has_option(helps.get(p, ""), opt) for p in progs):
                            report.fail(page, line, "`%s`: in no --help of %s"
                                        % (opt, ", ".join(sorted(progs))))
                for ident in re.findall(r"[A-Za-z_][\w.]*(?:\(\))?", span) if IDENT.match(span) else []:
                    name = ident.rstrip("()")
                    report.count("identifiers")
                    if name not in words and name not in tests:
                        report.fail(page, line, "`%s`: no such name in the sources or ctest" % name)
        # repository paths and file names anywhere in the text
        parents = tree_parents(text, tokens)
        for m in PATH_TOKEN.finditer(text):
            path = m.group(1).rstrip(".,;:)")
            if path.startswith("../") or text[max(0, m.start() - 2):m.start()] == "](":
                continue  # a link, checked above
            if path.startswith("ball/") and not path.endswith(".h"):
                continue  # a topic name (ball/segments), not a header
            if re.fullmatch(r"match/(\d+|\*|<id>|<m>)", path):
                continue  # a DDS partition (match/0, match/*), not server/match/
            lineno = line_of(text, m.start())
            if lineno in parents and text[text.rfind("\n", 0, m.start()) + 1:m.start()].strip() == "":
                path = parents[lineno] + path  # an entry of a folder tree
            first = path.split("/")[0]
            if first not in dir_names and first != "build":
                continue  # not a path of the repository (frames/, /tmp/...)
            if first == "build" and path.split("/")[1:2] not in (["libball"], ["server"], ["examples"]):
                continue  # what a verb writes into the build tree
            report.count("paths")
            if not exists_path(source, build, fileset, dirs, path):
                report.fail(page, lineno, "path %s: not in the repository%s"
                            % (path, " nor the build" if first == "build" else ""))
        for m in re.finditer(r"`(BALL_[A-Z0-9_]+)`\s*(?:\(|=\s*)([0-9][0-9.e+-]*)", text):
            report.count("constants")
            value = defines.get(m.group(1))
            try:
                same = value is not None and float(value) == float(m.group(2).rstrip("."))
            except ValueError:
                same = False
            if not same:
                report.fail(page, line_of(text, m.start()), "`%s` = %s: the sources say %s"
                            % (m.group(1), m.group(2), value))
        for m in BARE_FILE.finditer(text):
            name = m.group(1)
            if text[max(0, m.start() - 1):m.start()] == "/":
                continue
            report.count("file names")
            if name not in basenames:
                report.fail(page, line_of(text, m.start()), "file %s: no such file in the repository"
                            % name)
    return report.finish(["pages", "links", "code blocks", "paths", "options", "identifiers",
                          "constants", "section names"])


# ------------------------------------------------------------- commands mode

def runnable_blocks(source, page):
    _, tokens = parse(source, page)
    for i, t in enumerate(tokens):
        if t.type != "fence" or i == 0:
            continue
        prev = tokens[i - 1]
        if prev.type != "html_block":
            continue
        m = MARKER.match(prev.content.strip().splitlines()[-1])
        if m:
            yield t.map[0] + 2, m.group(1) or "", t.content


def steps_of(content):
    lines = content.splitlines()
    if any(l.startswith("$ ") for l in lines):
        steps, cur = [], None
        for l in lines:
            if l.startswith("$ "):
                cur = [l[2:], []]
                steps.append(cur)
            elif cur is not None:
                cur[1].append(l)
        return [(c, "\n".join(out)) for c, out in steps]
    return [(l, None) for l in lines if l.strip() and not l.strip().startswith("#")]


def scratch_root(source, build):
    root = tempfile.mkdtemp(prefix="docs_", dir=build)
    for entry in os.listdir(source):
        if entry in (".git",) or entry.startswith("build"):
            continue
        os.symlink(os.path.join(source, entry), os.path.join(root, entry))
    os.symlink(build, os.path.join(root, "build"))
    return root


def check_commands(args):
    report = Report(None)
    source, build = args.source, args.build
    env = dict(os.environ, BALL_BUILD_DIR=build, BALL_SOURCE_DIR=source)
    root = scratch_root(source, build)
    try:
        for page in pages_of(source, args.pages):
            report.count("pages")
            for line, kind, content in runnable_blocks(source, page):
                report.count("runnable blocks")
                if (kind == "long") != args.long:
                    if kind == "long":
                        report.notes.append(
                            "left to ./run docs-long, %s:%d: a long block (the demo, a benchmark)"
                            % (page, line))
                    continue
                for cmd, expected in steps_of(content):
                    run_one(report, page, line, kind, cmd, expected, root, env)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    needed = ["pages", "runnable blocks"] + (["commands run"] if args.long else
                                             ["commands run", "outputs compared"])
    return report.finish(needed)


def run_one(report, page, line, kind, cmd, expected, root, env):
    words = command_words(cmd) or []
    prog = program_of(words[0]) if words else None
    if prog in DDS_PROGRAMS and "--domain" not in options_of(words):
        report.fail(page, line, "`%s`: a DDS program in a runnable block needs --domain N" % cmd)
        return
    dds = prog in DDS_PROGRAMS or (prog == "./run" and words[1:2] in (["demo"], ["bench-server"]))
    if dds and kind != "long":
        report.fail(page, line, "`%s`: a DDS command runs only in a long block (./run docs-long)" % cmd)
        return
    if words and os.path.basename(words[0]) == "ctest":
        report.notes.append("listed, not run, %s:%d: `%s`: the tests it names run in this ctest "
                            "run themselves (long ones in ./run long)" % (page, line, cmd))
        cmd = cmd + " --show-only"
    report.count("commands run")
    # ./run configures its build with the source tree it lives in: it runs there
    cwd = env["BALL_SOURCE_DIR"] if words and words[0] == "./run" else root
    r = subprocess.run(["bash", "-o", "pipefail", "-c", cmd], cwd=cwd, env=env,
                       capture_output=True, text=True, timeout=3600)
    out = (r.stdout + r.stderr).rstrip("\n")
    if kind == "errors":
        if r.returncode == 0:
            report.fail(page, line, "`%s`: shown as an error, exits 0" % cmd)
    elif r.returncode != 0:
        report.fail(page, line, "`%s`: exit status %d:\n%s" % (cmd, r.returncode, out[-2000:]))
        return
    if words and os.path.basename(words[0]) == "ctest":
        m = re.search(r"Total Tests: (\d+)", out)
        if not m or int(m.group(1)) == 0:
            report.fail(page, line, "`%s`: finds no tests" % cmd)
    if expected is not None:
        report.count("outputs compared")
        if out != expected.rstrip("\n"):
            report.fail(page, line, "`%s` prints something else:\n--- the page\n%s\n--- the program\n%s"
                        % (cmd, expected, out))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mode", choices=["pages", "commands"])
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--pending")
    ap.add_argument("--long", action="store_true")
    ap.add_argument("--pages", nargs="+", help="these pages (relative to --source) instead of "
                    "README.md and docs/*.md")
    args = ap.parse_args()
    args.source, args.build = os.path.abspath(args.source), os.path.abspath(args.build)
    if args.mode == "pages":
        return check_pages(args)
    return check_commands(args)


if __name__ == "__main__":
    sys.exit(main())
