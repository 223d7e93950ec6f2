"""Text from user files made safe for one line of a terminal.

File, job and frame names reach progress and error lines; a name holding an escape sequence would
drive the terminal, a newline would split one error into two lines. one_line() writes every control
character (C0, DEL and C1, which includes ESC, CR and LF) and every character a UTF-8 stream cannot
carry as a backslash escape, so each message stays exactly one inert line.
"""
import re

_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029]")


def one_line(text: str) -> str:
    """`text` with control characters written as escapes (ESC -> \\x1b, LF -> \\n, U+2028 -> \\u2028)
    and lone surrogates (undecodable file-name bytes) as \\udcxx escapes."""
    escaped = _CONTROL.sub(lambda match: match.group(0).encode("unicode_escape").decode("ascii"), str(text))
    return escaped.encode("utf-8", "backslashreplace").decode("utf-8")
