/* The run-directory rule of docs/failure.md ("An output directory belongs to a run"), for
   sloshdyn_files: a run writes into a new directory beside its output directory and swaps it
   into place whole; a directory holding anything that no run of sloshdyn wrote (its marker
   file, MARKER, lists what a run wrote) is refused by name; every file is created new.
   python/sloshdyn/_files.py is the same rule for sloshdyn-py's own writers. Standard Fortran
   cannot list a directory, create a file exclusively or a directory under a unique name. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MARKER ".sloshdyn-run"

/* Create path as a new empty file (never an existing one, never through a symbolic link),
   readable by all; 0 or the errno. */
int sloshdyn_create_new(const char *path)
{
    int fd = open(path, O_CREAT | O_EXCL | O_WRONLY | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        return errno;
    close(fd);
    return 0;
}

/* mkdtemp: template (ending in XXXXXX) becomes the name of a new directory; 0 or the errno. */
int sloshdyn_make_temporary_directory(char *template)
{
    return mkdtemp(template) == NULL ? errno : 0;
}

/* The marker of directory dir, whole (NUL-terminated, malloc'd), or NULL when there is none
   or it does not start with header (then it is no marker of sloshdyn's). */
static char *read_marker(const char *dir, const char *header)
{
    char path[8192];
    struct stat s;
    if (snprintf(path, sizeof path, "%s/%s", dir, MARKER) >= (int)sizeof path)
        return NULL;
    if (lstat(path, &s) != 0 || !S_ISREG(s.st_mode) || s.st_size > (1 << 20))
        return NULL;
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    char *text = malloc((size_t)s.st_size + 1);
    size_t n = text ? fread(text, 1, (size_t)s.st_size, f) : 0;
    fclose(f);
    if (text == NULL)
        return NULL;
    text[n] = '\0';
    if (strncmp(text, header, strlen(header)) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

/* Whether name is a line of the marker's list (after its header). */
static int listed(const char *marker, const char *header, const char *name)
{
    size_t n = strlen(name);
    for (const char *line = marker + strlen(header); *line;) {
        const char *end = strchr(line, '\n');
        size_t length = end ? (size_t)(end - line) : strlen(line);
        if (length == n && strncmp(line, name, n) == 0)
            return 1;
        if (!end)
            break;
        line = end + 1;
    }
    return 0;
}

/* The first entry of directory dir that no run of sloshdyn wrote: not the marker and not a
   regular file (a symbolic link is not one) that the marker lists. 0: none (dir is empty or
   holds only a run's files, or does not exist); 1: name (capacity bytes, NUL-terminated) is
   that entry; otherwise the errno of reading dir. */
int sloshdyn_foreign_entry(const char *dir, const char *header, char *name, int capacity)
{
    DIR *d = opendir(dir);
    name[0] = '\0';
    if (d == NULL)
        return errno == ENOENT ? 0 : errno;
    char *marker = read_marker(dir, header);
    int found = 0;
    struct dirent *e;
    while (!found && (e = readdir(d)) != NULL) {
        char path[8192];
        struct stat s;
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        if (marker && strcmp(e->d_name, MARKER) == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (!marker || lstat(path, &s) != 0 || !S_ISREG(s.st_mode) ||
            !listed(marker, header, e->d_name)) {
            snprintf(name, (size_t)capacity, "%s", e->d_name);
            found = 1;
        }
    }
    closedir(d);
    free(marker);
    return found;
}

/* Remove a run's directory: the regular files its marker lists (every entry when all is
   nonzero: a run's own new directory), the marker, the directory. Anything else in it is
   left, and the directory with it (nothing that no run wrote is ever removed); 0 when it is
   gone. */
int sloshdyn_remove_run_directory(const char *dir, const char *header, int all)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return errno == ENOENT ? 0 : errno;
    char *marker = read_marker(dir, header);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        char path[8192];
        struct stat s;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        if ((all || (marker && listed(marker, header, e->d_name))) && lstat(path, &s) == 0 &&
            !S_ISDIR(s.st_mode))
            unlink(path);
    }
    closedir(d);
    if (marker) {
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, MARKER);
        unlink(path);
    }
    free(marker);
    return rmdir(dir) == 0 ? 0 : errno;
}

/* Put directory staging (complete, with its marker) in the place of target: a rename when
   target is missing or empty; otherwise target (checked again: a run's) moves to a new
   directory named by previous (a mkdtemp template beside it), staging takes its place and the
   previous run's directory is removed. A run that takes the place in between is replaced in
   turn, so two runs at once leave one whole run. 0; 1: target holds foreign (capacity bytes),
   refused; otherwise the errno of the step that failed. */
int sloshdyn_swap_into_place(const char *staging, const char *target, const char *previous,
                             const char *header, char *foreign, int capacity)
{
    chmod(staging, 0755);
    foreign[0] = '\0';
    for (int attempt = 0; attempt < 1000; attempt++) {
        if (rename(staging, target) == 0)
            return 0;
        if (errno != EEXIST && errno != ENOTEMPTY)
            return errno;
        int found = sloshdyn_foreign_entry(target, header, foreign, capacity);
        if (found != 0)
            return found;
        char old[8192];
        snprintf(old, sizeof old, "%s", previous);
        if (mkdtemp(old) == NULL)
            return errno;
        if (rename(target, old) != 0) {
            int cause = errno;
            rmdir(old);
            if (cause == ENOENT)
                continue;          /* another run moved it: try again */
            return cause;
        }
        int moved = rename(staging, target) == 0 ? 0 : errno;
        sloshdyn_remove_run_directory(old, header, 0);
        if (moved == 0)
            return 0;
        if (moved != EEXIST && moved != ENOTEMPTY)
            return moved;
    }
    return EBUSY;
}

/* The text of errno code, for messages (capacity bytes, NUL-terminated). */
void sloshdyn_error_text(int code, char *text, int capacity)
{
    snprintf(text, (size_t)capacity, "%s", strerror(code));
}

/* Whether path is a symbolic link (lstat). */
int sloshdyn_is_link(const char *path)
{
    struct stat s;
    return lstat(path, &s) == 0 && S_ISLNK(s.st_mode);
}
