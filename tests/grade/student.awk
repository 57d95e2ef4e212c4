# One student's results (tests/grade/grade.sh) as their row of the gradebook, their row of
# statuses.csv and their Gradescope results.json. Reads, in this order:
#   weights.tsv    <id>\t<points>, every exercise graded
#   exercises.tsv  <lesson folder>\t<id>\t<title>, in the gradebook's order
#   results.tsv    <id>\t<status>\t<message>, the message escaped as --results writes it
#                  (\\, \n, \t; valid UTF-8, no other control character)
# -v row=<file> -v srow=<file>; in the environment (awk -v would read backslashes as escapes)
# NAME=<student> (no control character), NOTES=<a message about the whole submission, escaped
# the same way> and JSON=<the results.json file to write>.
BEGIN { FS = "\t"; name = ENVIRON["NAME"]; notes = ENVIRON["NOTES"]; json = ENVIRON["JSON"] }
FILENAME == ARGV[1] { points[$1] = $2; next }
FILENAME == ARGV[2] { order[++n] = $2; title[$2] = $3; next }
{ status[$1] = $2; message[$1] = $3 }

# Raw text (no control character) in the escaped form: backslashes doubled.
function escape(s,    out, i, c) {
  out = ""
  for (i = 1; i <= length(s); i++) {
    c = substr(s, i, 1)
    out = out (c == "\\" ? "\\\\" : c)
  }
  return out
}
# The escaped form as the inside of a JSON string: its escapes are JSON's; quotes added.
function json_text(s,    parts, k, out, i) {
  k = split(s, parts, "\"")
  out = parts[1]
  for (i = 2; i <= k; i++) out = out "\\\"" parts[i]
  return out
}
function csv(s) {
  if (s ~ /[",]/ || s ~ /^ / || s ~ / $/) {
    gsub(/"/, "\"\"", s)
    s = "\"" s "\""
  }
  return s
}
function words(st) {
  if (st == "pass") return "pass"
  if (st == "fail") return "FAIL"
  if (st == "not-done") return "not done"
  if (st == "does-not-compile") return "does not compile"
  if (st == "timed-out") return "timed out"
  if (st == "out-of-memory") return "out of memory"
  if (st == "forbidden-call") return "calls the function it reproduces"
  if (st ~ /^crashed:/) return "crashed (" substr(st, 9) ")"
  return st
}

END {
  line = csv(name)
  sline = csv(name)
  total = 0
  max = 0
  tests = ""
  for (k = 1; k <= n; k++) {
    id = order[k]
    st = (id in status) ? status[id] : "crashed"
    w = points[id]
    got = st == "pass" ? w : 0
    total += got
    max += w
    line = line "," got
    sline = sline "," csv(words(st))
    out = escape(words(st)) (message[id] == "" ? "" : "\\n" message[id])
    tests = tests (k > 1 ? ",\n" : "") \
      "    {\"name\": \"" json_text(escape(id " " title[id])) "\", \"number\": \"" id "\"" \
      ", \"score\": " got ", \"max_score\": " w \
      ", \"status\": \"" (st == "pass" ? "passed" : "failed") "\"" \
      ", \"output\": \"" json_text(out) "\", \"visibility\": \"visible\"}"
  }
  print line "," sprintf("%g", total) > row
  print sline > srow
  printf "{\n  \"score\": %g,\n", total > json
  printf "  \"output\": \"%s\",\n", json_text(escape(name ": " sprintf("%g", total) " of " \
    sprintf("%g", max) " points") (notes == "" ? "" : "\\n" notes)) > json
  printf "  \"visibility\": \"visible\",\n  \"tests\": [\n%s\n  ]\n}\n", tests > json
}
