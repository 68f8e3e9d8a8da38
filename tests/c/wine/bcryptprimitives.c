/*
 * A stand-in for Windows' bcryptprimitives.dll, for the tests under Wine ONLY: Wine 8 has
 * no bcryptprimitives.dll, and the Rust standard library of the DLL imports ProcessPrng
 * from it (for the random keys of its hash maps). Real Windows (8 and later) has it.
 * scripts/cross_tests.sh builds this with mingw and puts it beside the test programs in
 * target/cross_tests; it is never put into an archive.
 *
 * ProcessPrng(buffer, size) fills the buffer with random bytes and returns TRUE; here
 * through RtlGenRandom (advapi32's SystemFunction036), which Wine has.
 */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T size) {
    while (size > 0) {
        ULONG chunk = size > 0x40000000u ? 0x40000000u : (ULONG)size;
        if (!SystemFunction036(data, chunk)) return FALSE;
        data += chunk;
        size -= chunk;
    }
    return TRUE;
}
