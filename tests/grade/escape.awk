# Text as one message field of a results line (tests/grade/grade.sh; the format of
# exercise_main.cpp's --results): backslash, tab and newline written \\, \t and \n, so that the
# whole text is one field of one line. The caller removes the other control characters first.
{
  out = ""
  n = length($0)
  for (i = 1; i <= n; i++) {
    c = substr($0, i, 1)
    if (c == "\\") out = out "\\\\"
    else if (c == "\t") out = out "\\t"
    else out = out c
  }
  printf "%s%s", (NR > 1 ? "\\n" : ""), out
}
