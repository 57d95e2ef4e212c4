// The translation unit that builds a precompiled header (lib/support/pch.cmake).
