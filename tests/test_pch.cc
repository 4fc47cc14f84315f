// The translation unit that compiles the test binaries' shared precompiled header.
