// The translation unit that builds a precompiled header (tests/support/pch.cmake).
