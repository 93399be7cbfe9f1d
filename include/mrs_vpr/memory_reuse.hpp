#pragma once

namespace mrs_vpr {

/**
 * Asks the C library's allocator to keep the memory a query frees for the next query, instead of
 * handing it back to the kernel and faulting it in again. A query allocates tens of megabytes of
 * matrices; on machines where the kernel faults pages in slowly (virtual machines) that costs more
 * than the query's arithmetic: on a 100k-frame map MRS took 70-127 ms a query without this and
 * 21-35 ms with it (mrs_vpr_map_scale_benchmark). The price: the process keeps its largest query's
 * working set resident (about N x M x 4 bytes for the brute force, up to 32 MB a buffer).
 *
 * Process-wide, so only a program's main() should call it (the node, the tools and the benchmarks
 * do; the nodelet does not, as the manager's process is not its own). Does nothing where the C
 * library is not glibc.
 */
void retainFreedMemory();

}  // namespace mrs_vpr
