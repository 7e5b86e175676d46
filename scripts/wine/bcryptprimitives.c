/* Test fixture for wine only, never shipped: Debian 12's wine 8.0 lacks bcryptprimitives.dll,
 * which every Windows since 10 has and from which Rust's standard library (the FMU's DLL and the
 * test master) imports ProcessPrng. This stand-in answers it with BCryptGenRandom, which wine has.
 * Built by scripts/test-platforms with mingw-w64 and put beside the test master's .exe. */
#include <windows.h>
#include <bcrypt.h>

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length)
{
    while (length > 0) {
        ULONG chunk = length > 0x40000000 ? 0x40000000 : (ULONG)length;
        if (BCryptGenRandom(NULL, data, chunk, BCRYPT_USE_SYSTEM_PREFERRED_RNG) != 0)
            return FALSE;
        data += chunk;
        length -= chunk;
    }
    return TRUE;
}
