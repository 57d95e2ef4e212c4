# The class report, class.md (tests/grade/grade.sh), from every graded student's results.
# Reads, in this order:
#   exercises.tsv  <lesson folder>\t<id>\t<title>, in the gradebook's order
#   all.tsv        <student>\t<id>\t<status>\t<message>, the message escaped as exercise_main's
#                  --results writes it (\\, \n, \t)
# -v students=<how many were graded> -v when=<date> -v lessons=<the lessons graded>
# -v stopped=<a sentence when the run stopped early, or "">.
# A student counts once per mistake or symptom of an exercise, however often the checker said
# it. Symptoms are grouped with their numbers left out ("N of those N cases fail").
BEGIN { FS = "\t" }
FILENAME == ARGV[1] { order[++n] = $2; title[$2] = $3; next }
{
  id = $2
  st = $3
  count[id, st]++
  if (st ~ /^crashed/) count[id, "crashed"]++
  text = decode($4)
  k = split(text, lines, "\n")
  for (i = 1; i <= k; i++) {
    l = lines[i]
    sub(/^ +/, "", l)
    if (l ~ /^likely mistake \(/) {
      key = id "\t" l
      if (!(($1, key) in seen_m)) { seen_m[$1, key] = 1; if (!(key in mistakes)) m_order[++nm] = key; mistakes[key]++ }
    } else if (l ~ /^symptom: / || (i == 1 && l ~ /^stopped/)) {
      gsub(/[0-9]+/, "N", l)
      key = id "\t" l
      if (!(($1, key) in seen_s)) { seen_s[$1, key] = 1; if (!(key in symptoms)) s_order[++ns] = key; symptoms[key]++ }
    }
  }
}

function decode(s,    out, i, c, d) {
  out = ""
  for (i = 1; i <= length(s); i++) {
    c = substr(s, i, 1)
    if (c == "\\" && i < length(s)) {
      d = substr(s, ++i, 1)
      out = out (d == "n" ? "\n" : d == "t" ? "\t" : d)
    } else out = out c
  }
  return out
}
function cnt(id, st) { return (id, st) in count ? count[id, st] : 0 }
# s with every "|" written "\|" (a Markdown table's cell).
function bars(s,    out, at) {
  out = ""
  while ((at = index(s, "|")) > 0) {
    out = out substr(s, 1, at - 1) "\\|"
    s = substr(s, at + 1)
  }
  return out s
}
function listed(keys, counts, m,    j, id, text) {
  if (m == 0) { print "None."; return }
  for (j = 1; j <= m; j++) {
    id = keys[j]
    sub(/\t.*/, "", id)
    text = substr(keys[j], length(id) + 2)
    print "- " id " (" title[id] "): " counts[keys[j]] " of " students " — " text
  }
}

END {
  print "# Class report"
  print ""
  print students " submission" (students == 1 ? "" : "s") " graded on " when ", lessons " lessons \
    " (" n " exercises; make grade, tests/grade/grade.sh)." (stopped == "" ? "" : " " stopped)
  print ""
  print "## Pass rate"
  print ""
  print "| exercise | pass | FAIL | not done | does not compile | timed out | crashed | out of memory | calls the function it reproduces | pass rate |"
  print "|---|---|---|---|---|---|---|---|---|---|"
  for (j = 1; j <= n; j++) {
    id = order[j]
    rate = students > 0 ? sprintf("%d%%", 100 * cnt(id, "pass") / students + 0.5) : "-"
    print "| " id " " bars(title[id]) " | " cnt(id, "pass") " | " cnt(id, "fail") " | " cnt(id, "not-done") \
      " | " cnt(id, "does-not-compile") " | " cnt(id, "timed-out") " | " cnt(id, "crashed") " | " \
      cnt(id, "out-of-memory") " | " cnt(id, "forbidden-call") " | " rate " |"
  }
  print ""
  print "## The classic mistakes the checker named"
  print ""
  print "Each: the exercise, how many students made it, and the checker's words. The grader runs"
  print "the checker as for a student who has read every hint: a level 3 exercise's mistake is"
  print "named too, here and in the students' feedback."
  print ""
  listed(m_order, mistakes, nm)
  print ""
  print "## The symptoms it reported"
  print ""
  print "Where no mistake of the catalogue matched, what was measured; and how runs stopped"
  print "(numbers written N)."
  print ""
  listed(s_order, symptoms, ns)
  print ""
  print "## Exercises nobody attempted"
  print ""
  none = 0
  for (j = 1; j <= n; j++) {
    id = order[j]
    if (students > 0 && cnt(id, "not-done") == students) { print "- " id " " title[id]; none++ }
  }
  if (none == 0) print "None: every exercise was attempted by at least one student."
}
