/* The type and size of a file by stat(2), for sloshdyn_files (file_type): standard Fortran
   cannot tell a regular file from a FIFO or a device before opening it, and opening a FIFO
   blocks until a writer comes; reading /dev/zero never ends. */
#include <errno.h>
#include <stdint.h>
#include <sys/stat.h>

/* 0: no such file; 1: a regular file (*size its bytes); 2: a directory; 3: anything else (a
   FIFO, a device, a socket); -1: stat failed for another reason (e.g. permission denied). */
int sloshdyn_file_type(const char *path, int64_t *size)
{
    struct stat s;
    *size = 0;
    if (stat(path, &s) != 0)
        return (errno == ENOENT || errno == ENOTDIR) ? 0 : -1;
    if (S_ISDIR(s.st_mode))
        return 2;
    if (!S_ISREG(s.st_mode))
        return 3;
    *size = (int64_t)s.st_size;
    return 1;
}
