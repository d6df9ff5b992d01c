#pragma once
// Transparent huge pages for glibc's malloc, which the program and Mesa's llvmpipe allocate
// through.
//
// A frame touches hundreds of megabytes for the first time (decoded textures and their mip
// chains, the G-buffer, llvmpipe's copies of every buffer, the cuts' texels), and where the
// kernel backs them with 4 KiB pages each first touch takes a page fault. On the 2-core test
// machine (a virtual machine) writing 64 MiB the first time took 160 ms with 4 KiB pages, 64 ms
// with 2 MiB ones, 3 ms the second time. glibc ≥ 2.35 asks for huge pages for the blocks it
// maps and the heap it grows when the tunable glibc.malloc.hugetlb=1 is set, and reads
// tunables only as a process starts; the kernel gives them only on request where its mode is
// "madvise", Debian's default. Measured (docs/performance.md): DamagedHelmet's whole render
// 3.2–3.4 → 1.6–1.7 s, 65,536 mixed lights at 640×480 (lightcuts, ε = 0.02) 1.07–1.11 →
// 0.83–0.89 s, the same with the reference within the runs' spread; peak memory within 4%.
namespace manylight {

// Runs this program again with the same arguments (execv of /proc/self/exe) and
// glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES. Returns instead where that tunable is set
// already (so also in the program run again), where MANYLIGHT_HUGE_PAGES=0, where the
// kernel's mode is not "madvise" (with "always" every large block gets huge pages anyway;
// with "never" none do), in a secure-execution process (setuid: glibc ignores the tunables),
// under Valgrind (the program run again would run without it), or where exec fails. Call it
// first thing in main, before any thread starts.
void restartWithHugePages(char** argv);

}  // namespace manylight
