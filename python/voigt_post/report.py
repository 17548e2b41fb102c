"""Report helpers of the perf studies and the cases' tables (Python standard library only):
numbers for Markdown tables, medians over repeats, a README section rewritten between two
marker lines."""
import statistics


def fmt(x, digits=4):
    """x to DIGITS significant digits ("-" for None, 3 digits from 1e4 up)."""
    if x is None:
        return "-"
    if x == 0:
        return "0"
    if abs(x) >= 1e4:
        return "%.3g" % x
    return "%.*g" % (digits, x)


def med(xs):
    """Median of the values that are not None; None when there are none."""
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def spread(xs, f=fmt):
    """"min-max" of the values that are not None, "-" when there are none."""
    xs = [x for x in xs if x is not None]
    return "%s-%s" % (f(min(xs)), f(max(xs))) if xs else "-"


def failed_runs(items):
    """A "## Failed runs" section: items are (one-line description, log text) per run."""
    out = ["", "## Failed runs"]
    for line, text in items:
        out += ["", "- " + line, "", "```\n%s\n```" % text.strip()]
    return out


def splice(text, begin, end, lines):
    """TEXT with what lies between its lines BEGIN and END replaced by LINES (a list of lines)."""
    a, rest = text.split(begin, 1)
    b = rest.split(end, 1)[1] if end in rest else ""
    return a + begin + "\n" + "\n".join(lines) + "\n" + end + b


def replace_section(path, begin, end, lines, title):
    """Rewrites PATH's text between the lines BEGIN and END with LINES (a new file headed
    "# TITLE", or the markers appended, when they are not there yet)."""
    try:
        with open(path) as f:
            text = f.read()
    except FileNotFoundError:
        text = "# %s\n\n%s\n%s\n" % (title, begin, end)
    if begin not in text:
        text += "\n%s\n%s\n" % (begin, end)
    with open(path, "w") as f:
        f.write(splice(text, begin, end, lines))


def replace_marked(path, begin, end, text, who):
    """The cases' table.py --readme: PATH's text between its markers BEGIN and END becomes TEXT;
    a file without both markers is left alone and the program ends with WHO's message."""
    with open(path) as f:
        doc = f.read()
    if begin not in doc or end not in doc:
        raise SystemExit("%s: %s has no %s ... %s markers" % (who, path, begin, end))
    with open(path, "w") as f:
        f.write(splice(doc, begin, end, [text]))
