"""The Jinja2 environment of the report's pages (reports/templates/): autoescape on, so every value
from the results is escaped where it is inserted; a value is inserted unescaped only through a
filter below that escapes its text itself (md_inline). Jinja2 is Debian's python3-jinja2."""

import functools
import os
import re
import sys
import urllib.parse

try:
    import jinja2
    import markupsafe
except ImportError:
    sys.exit("glintlab: error: the report's templates need Jinja2 in /usr/bin/python3 "
             "(Debian's python3-jinja2; scripts/setup.sh installs it)")

TEMPLATES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "templates")


def fmt(x, spec=".3g"):
    """A number formatted, "–" when there is none."""
    return "–" if x is None else format(x, spec)


def md_inline(text):
    """One line of Markdown text as HTML: escaped, then `code` and **bold** rendered."""
    h = str(markupsafe.escape(text))
    h = re.sub(r"`([^`]+)`", r"<code>\1</code>", h)
    return markupsafe.Markup(re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", h))


@functools.lru_cache(maxsize=None)
def environment():
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                             autoescape=True, undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True)
    env.filters["url"] = urllib.parse.quote
    env.filters["fmt"] = fmt
    env.filters["spec"] = format
    env.filters["md_inline"] = md_inline
    return env


def render(template, **values):
    return environment().get_template(template).render(**values)
