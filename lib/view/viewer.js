// Placeholder: the viewer's code is written in lib/view/ on its own branch (issue 14).
"use strict";
