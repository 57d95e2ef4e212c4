# The exercise statements of a lesson (exercises/NN-topic/exercises.hpp), one line each:
#   id TAB function TAB level TAB title TAB forbidden TAB voids TAB declaration TAB outs
# id "5.1"; level "1, 15 min, uses 5.1" (from "*Level 1 of 3, about 15 min; uses 5.1.*");
# title the bold title without "Exercise N.K: "; forbidden the soa:: names of its "Do not
# call" sentence, comma separated; voids "(void)a, (void)b;" for its parameters; declaration
# the function's declaration as written, its lines joined by "\001", without the ";"; outs
# the parameters it writes (non-const references), comma separated.
# Read by tests/exercises/stubs.sh (make stubs, ctest exercises.stubs) and
# tests/exercises/recording.sh (make grade's recorders and replayers).
function flush(   t, i, meta, low, s, name, decl1, params, depth, c, p, n, voids, word, outs) {
  if (id == "") return
  t = doc
  i = index(t, "**Exercise " id)
  t = substr(t, i + length("**Exercise " id))
  sub(/^:? */, "", t)
  i = index(t, "**")
  title = substr(t, 1, i - 1)
  sub(/\.$/, "", title)
  meta = ""
  if (match(doc, /\*Level [1-3] of 3, about [0-9]+ min[^*]*\*/)) {
    meta = substr(doc, RSTART + 7, RLENGTH - 8)
    sub(/ of 3, about /, ", ", meta)
    sub(/;/, ",", meta)
    sub(/\.$/, "", meta)
  }
  forbidden = ""
  low = tolower(doc)
  i = index(low, "do not call ")
  if (i) {
    s = substr(doc, i + 12)
    if (match(s, /\.( |$)/)) s = substr(s, 1, RSTART - 1)
    while (match(s, /soa::[A-Za-z_][A-Za-z0-9_:]*/)) {
      word = substr(s, RSTART, RLENGTH)
      s = substr(s, RSTART + RLENGTH)
      if (word ~ /::operator$/ && match(s, /^[^ ,]+/)) {
        word = word substr(s, 1, RLENGTH)
        s = substr(s, RLENGTH + 1)
      }
      sub(/:+$/, "", word)
      sub(/\(\)$/, "", word)
      if (index(", " forbidden ", ", ", " word ", ") == 0)
        forbidden = forbidden (forbidden == "" ? "" : ", ") word
    }
  }
  decl1 = decl
  gsub(/\001/, " ", decl1)
  i = index(decl1, "(")
  name = substr(decl1, 1, i - 1)
  sub(/^.*[^A-Za-z0-9_]/, "", name)
  # The parameters: split at the commas outside <>, () and {}.
  params = substr(decl1, i + 1)
  depth = 0
  n = 0
  p = ""
  voids = ""
  outs = ""
  for (c = 1; c <= length(params); c++) {
    ch = substr(params, c, 1)
    if (ch == "(" || ch == "<" || ch == "{") depth++
    if ((ch == ")" || ch == ">" || ch == "}") && depth > 0) { depth--; if (ch != ")" || depth >= 0) { p = p ch; continue } }
    if ((ch == "," || ch == ")") && depth == 0) {
      sub(/ *=.*$/, "", p)
      if (match(p, /[A-Za-z_][A-Za-z0-9_]* *$/)) {
        word = substr(p, RSTART, RLENGTH)
        sub(/ *$/, "", word)
        if (word != "void") voids = voids (voids == "" ? "" : ", ") "(void)" word
        if (p ~ /&/ && p !~ /&&/ && p !~ /(^|[^A-Za-z0-9_])const([^A-Za-z0-9_]|$)/)
          outs = outs (outs == "" ? "" : ", ") word
      }
      p = ""
      if (ch == ")") break
      continue
    }
    p = p ch
  }
  if (voids != "") voids = voids ";"
  print id "\t" name "\t" meta "\t" title "\t" forbidden "\t" voids "\t" decl "\t" outs
  id = ""
}
/^\/\/\/ \*\*Exercise [0-9]+\.[0-9]+[: ]/ {
  flush()
  id = $3
  sub(/:$/, "", id)
  doc = ""
  decl = ""
  state = "doc"
}
state == "doc" && /^ *\/\/\// {
  line = $0
  sub(/^ *\/\/\/ ?/, "", line)
  doc = doc " " line
  next
}
state == "doc" { state = "decl" }
state == "decl" {
  line = $0
  decl = decl (decl == "" ? "" : "\001") line
  if (line ~ /; *$/) {
    sub(/; *$/, "", decl)
    state = ""
    flush()
  }
}
END { flush() }
