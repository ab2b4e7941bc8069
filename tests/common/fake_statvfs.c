/* A test double for the free space of a file system: preloaded into the fluidem binary
 * (LD_PRELOAD), statvfs and statvfs64 report FLUIDEM_FAKE_FREE_BYTES bytes available (and free)
 * on every file system; without that variable they report what the system does. Used by
 * tests/unit/app/output_integrity_test.cpp for the disk-space checks before a run. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <sys/statvfs.h>

static void fake_free(unsigned long frsize, fsblkcnt_t* bavail, fsblkcnt_t* bfree) {
  const char* v = getenv("FLUIDEM_FAKE_FREE_BYTES");
  if (v == NULL || frsize == 0) return;
  const unsigned long long bytes = strtoull(v, NULL, 10);
  *bavail = (fsblkcnt_t)(bytes / frsize);
  *bfree = *bavail;
}

int statvfs(const char* path, struct statvfs* s) {
  int (*real)(const char*, struct statvfs*) =
      (int (*)(const char*, struct statvfs*))dlsym(RTLD_NEXT, "statvfs");
  const int rc = real(path, s);
  if (rc == 0) fake_free(s->f_frsize, &s->f_bavail, &s->f_bfree);
  return rc;
}

int statvfs64(const char* path, struct statvfs64* s) {
  int (*real)(const char*, struct statvfs64*) =
      (int (*)(const char*, struct statvfs64*))dlsym(RTLD_NEXT, "statvfs64");
  const int rc = real(path, s);
  if (rc == 0) fake_free(s->f_frsize, &s->f_bavail, &s->f_bfree);
  return rc;
}
