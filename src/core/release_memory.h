#pragma once

// Gives the heap's free pages back to the operating system. A long SLAM run frees the
// particles' maps (hundreds of megabytes in 4 KB patches) before it builds the final map; the
// allocator keeps those pages mapped, scattered between live blocks, so the final passes would
// otherwise raise the process's resident memory on top of them. A no-op where the C library
// has no such call.
namespace semchain {

void ReleaseFreeMemory();

}  // namespace semchain
