/*
 * An HDF5 file driver for the results file being written: HDF5's default
 * driver (sec2: POSIX pread and pwrite), except that the file's growth goes to the disk
 * around the kernel's page cache.
 *
 * Why: a results file grows at its end (`FileSpaceStrategy::None`), a history chunk at a
 * time: 16 KB a point for a modal history study, 30 MB for the bench's. Through the page
 * cache, each byte is copied into a page, then written back by the kernel's threads, on the
 * same cores as the workers: about a tenth of the study's CPU time on the development
 * machine. Written with O_DIRECT, the disk takes the bytes from this process's buffer.
 *
 * How: writes that continue one another are gathered in a buffer that starts on a block
 * boundary; each whole megabyte goes to the disk in one O_DIRECT write. The rest of the
 * buffer (less than a block past the last whole one) stays, and goes through the page
 * cache when the caller needs every byte in the OS (`batstudy_direct_flush`: before the
 * journal names them), on every flush, truncate and close, and before a read or a write
 * elsewhere touches it. Every other write (HDF5 rewriting its metadata in place) and every
 * read goes through the page cache as with sec2; an O_DIRECT write makes the kernel write
 * back and drop its pages over the same range first, so both views stay one file. Where
 * the file system refuses O_DIRECT, everything goes through the page cache.
 *
 * A thread of its own syncs the file every few blocks (SYNC_BYTES), so that the disk makes
 * the bytes durable while the run goes on, not all at its final fsync; waiting for a block
 * to be written never waits for a sync.
 *
 * Written against the HDF5 headers it is compiled with: 1.10 (Debian's) and 1.14 / 2.x
 * (the wheel's), whose driver structures differ; the fields are set by name.
 */
#define _GNU_SOURCE
#include <hdf5.h>
#if H5_VERSION_GE(1, 13, 0)
#include <H5FDdevelop.h>
#endif

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

/* The alignment O_DIRECT needs of offsets, lengths and memory (the largest logical block
 * size of common disks), and the bytes written at once. */
#define ALIGN ((size_t)4096)
#define BLOCK_BYTES ((size_t)1 << 20)
#define BUFFER_BYTES (2 * BLOCK_BYTES + ALIGN)
/* The block writer makes the file durable (fdatasync) after each this many bytes. A write
 * with O_DIRECT leaves the bytes in the disk's volatile cache, and the run's final fsync
 * waits while the disk makes all of them durable at once, after the last point: 50 ms of
 * the bench's 0.5 s modal history study (28 MiB) on the development machine, on the
 * critical path. Synced as the file grows, while the workers compute, the final fsync
 * finds less than this many bytes left (0.2 ms there). The syncs run on a thread of their
 * own ("batstudy-sync"). A sync took 9 to 20 ms on the development machine, and while the
 * block writer made it, whoever waited for a block waited for the sync too: the writer
 * thread sending what it gathered before the journal names it, HDF5 reading or rewriting
 * metadata. On a 9 000-point modal history study the writer thread waited 203 ms for
 * blocks with the syncs on the block writer, 136 ms without (medians of five runs). */
#define SYNC_BYTES (4 * BLOCK_BYTES)

typedef struct {
    H5FD_t pub; /* first: what HDF5 sees of the file */
    int fd;     /* through the page cache */
    int direct; /* O_DIRECT, or -1 */
    haddr_t eoa;
    haddr_t eof; /* the file's size with the buffer written */
    dev_t dev;
    ino_t ino;
    unsigned char *bufs[2]; /* BUFFER_BYTES each, aligned: one gathers, one is written */
    unsigned char *buf;     /* the one gathering */
    haddr_t start;          /* the file offset of buf[0]: a multiple of ALIGN */
    size_t len;             /* bytes in the buffer */
    size_t in_os;           /* buf[0..in_os] is in the file already */
    /* The writer of whole blocks: a thread, so that the disk works while HDF5 goes on
     * (a write with O_DIRECT returns when the disk has the bytes). One block at a time.
     * And the syncer, which makes the file durable every SYNC_BYTES the block writer
     * wrote, while the block writer goes on. Both under `mu`, signalled on `cv`. */
    pthread_t thread;
    int thread_running;
    pthread_t syncer;
    int syncer_running;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int busy;   /* a block is handed over and not written yet */
    int sync_due; /* the syncer is asked to sync, or syncing */
    int quit;
    const unsigned char *job;
    size_t job_len;
    haddr_t job_at;
    int failed;  /* errno of a block that could not be written or synced, or 0 */
    size_t unsynced; /* bytes the block writer wrote since it last asked for a sync */
    int refused; /* the file system refused O_DIRECT: blocks go through the page cache */
} direct_t;

static const H5FD_class_t *direct_class(void);

static int pwrite_all(int fd, const unsigned char *p, size_t size, haddr_t at) {
    while (size > 0) {
        ssize_t n = pwrite(fd, p, size, (off_t)at);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return -1;
        p += n;
        size -= (size_t)n;
        at += (haddr_t)n;
    }
    return 0;
}

/* Read `size` bytes at `at` through the page cache; zeros past the end of the file. */
static int pread_all(int fd, unsigned char *p, size_t size, haddr_t at) {
    while (size > 0) {
        ssize_t n = pread(fd, p, size, (off_t)at);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return -1;
        if (n == 0) {
            memset(p, 0, size);
            break;
        }
        p += n;
        size -= (size_t)n;
        at += (haddr_t)n;
    }
    return 0;
}

/* One block to the disk: with O_DIRECT, or through the page cache where the file system
 * refuses it (EINVAL, once: then always). errno on failure. */
static int write_block(direct_t *f, const unsigned char *p, size_t size, haddr_t at) {
    if (!f->refused && pwrite_all(f->direct, p, size, at) == 0)
        return 0;
    if (!f->refused && errno != EINVAL)
        return errno ? errno : EIO;
    f->refused = 1;
    return pwrite_all(f->fd, p, size, at) == 0 ? 0 : (errno ? errno : EIO);
}

/* With `mu` held: wait until `*asked` (a task for this thread) or the file closes; whether
 * there is a task. A task given before the close is still done. */
static int next_task(direct_t *f, const int *asked) {
    while (!*asked && !f->quit)
        pthread_cond_wait(&f->cv, &f->mu);
    return *asked;
}

/* With `mu` held: the task is done, with errno `e` (0: it worked). The first failure is
 * the run's, reported by the next wait or the close. */
static void task_done(direct_t *f, int *asked, int e) {
    if (e != 0 && f->failed == 0)
        f->failed = e;
    *asked = 0;
    pthread_cond_broadcast(&f->cv);
}

static void *block_writer(void *arg) {
    direct_t *f = arg;
#ifdef __linux__
    pthread_setname_np(pthread_self(), "batstudy-disk"); /* as profilers show it */
#endif
    pthread_mutex_lock(&f->mu);
    while (next_task(f, &f->busy)) {
        const unsigned char *p = f->job;
        size_t size = f->job_len;
        haddr_t at = f->job_at;
        pthread_mutex_unlock(&f->mu);
        int e = write_block(f, p, size, at);
        pthread_mutex_lock(&f->mu);
        /* while a sync is under way these bytes count towards the next one */
        if (e == 0)
            f->unsynced += size;
        if (f->unsynced >= SYNC_BYTES && !f->sync_due && f->syncer_running) {
            f->unsynced = 0;
            f->sync_due = 1;
        }
        task_done(f, &f->busy, e);
    }
    pthread_mutex_unlock(&f->mu);
    return NULL;
}

static void *syncer(void *arg) {
    direct_t *f = arg;
#ifdef __linux__
    pthread_setname_np(pthread_self(), "batstudy-sync");
#endif
    pthread_mutex_lock(&f->mu);
    while (next_task(f, &f->sync_due)) {
        pthread_mutex_unlock(&f->mu);
        /* a failure is the run's: the error is reported once, to this descriptor, and the
         * final fsync (on another) would not see it */
        int e = fdatasync(f->fd) < 0 ? (errno ? errno : EIO) : 0;
        pthread_mutex_lock(&f->mu);
        task_done(f, &f->sync_due, e);
    }
    pthread_mutex_unlock(&f->mu);
    return NULL;
}

/* Wait for the block handed over to be written (not for a sync); -1 if a block could not
 * be written, or a sync failed. */
static herr_t wait_idle(direct_t *f) {
    if (!f->thread_running)
        return 0;
    pthread_mutex_lock(&f->mu);
    while (f->busy)
        pthread_cond_wait(&f->cv, &f->mu);
    int e = f->failed;
    f->failed = 0;
    pthread_mutex_unlock(&f->mu);
    if (e != 0) {
        errno = e;
        return -1;
    }
    return 0;
}

/* Put the buffer's bytes not in the file yet into the OS, through the page cache; they
 * stay in the buffer, for the whole block's O_DIRECT write. */
static herr_t to_os(direct_t *f) {
    if (f->in_os < f->len &&
        pwrite_all(f->fd, f->buf + f->in_os, f->len - f->in_os, f->start + f->in_os) < 0)
        return -1;
    f->in_os = f->len;
    return 0;
}

/* Hand the buffer's whole blocks to the block writer (once it is done with the last ones),
 * and go on gathering in the other buffer, from what is left. Without a thread or with
 * O_DIRECT refused, they are written here. */
static herr_t write_blocks(direct_t *f) {
    size_t whole = f->len / ALIGN * ALIGN;
    if (whole == 0)
        return 0;
    if (wait_idle(f) < 0)
        return -1;
    if (!f->thread_running || f->refused) {
        /* here: O_DIRECT takes whole aligned blocks; the page cache only what it lacks */
        int e = !f->refused ? write_block(f, f->buf, whole, f->start)
                : f->in_os < whole
                    ? write_block(f, f->buf + f->in_os, whole - f->in_os, f->start + f->in_os)
                    : 0;
        if (e != 0) {
            errno = e;
            return -1;
        }
        memmove(f->buf, f->buf + whole, f->len - whole);
    } else {
        unsigned char *next = f->bufs[f->buf == f->bufs[0]];
        memcpy(next, f->buf + whole, f->len - whole);
        pthread_mutex_lock(&f->mu);
        f->job = f->buf;
        f->job_len = whole;
        f->job_at = f->start;
        f->busy = 1;
        pthread_cond_broadcast(&f->cv);
        pthread_mutex_unlock(&f->mu);
        f->buf = next;
    }
    f->start += whole;
    f->len -= whole;
    f->in_os = f->in_os > whole ? f->in_os - whole : 0;
    return 0;
}

/* Everything gathered written (the blocks to the disk, the rest into the OS), and the
 * buffer emptied. */
static herr_t write_all_gathered(direct_t *f) {
    if (write_blocks(f) < 0 || wait_idle(f) < 0 || to_os(f) < 0)
        return -1;
    f->start += f->len;
    f->len = 0;
    f->in_os = 0;
    return 0;
}

/* Start gathering at `addr`: the buffer begins at the block boundary below it, with the
 * file's bytes between the two. */
static herr_t begin_at(direct_t *f, haddr_t addr) {
    f->start = addr / ALIGN * ALIGN;
    f->len = (size_t)(addr - f->start);
    f->in_os = f->len;
    return pread_all(f->fd, f->buf, f->len, f->start) < 0 ? -1 : 0;
}

/* Stop the block writer and the syncer, once each has done what it was given; the error
 * of the last of them (errno), or 0. */
static int stop_threads(direct_t *f) {
    pthread_mutex_lock(&f->mu);
    f->quit = 1;
    pthread_cond_broadcast(&f->cv);
    pthread_mutex_unlock(&f->mu);
    if (f->thread_running)
        pthread_join(f->thread, NULL);
    if (f->syncer_running)
        pthread_join(f->syncer, NULL);
    f->thread_running = f->syncer_running = 0;
    int e = f->failed;
    f->failed = 0;
    return e;
}

static void free_file(direct_t *f) {
    stop_threads(f);
    pthread_mutex_destroy(&f->mu);
    pthread_cond_destroy(&f->cv);
    if (f->direct >= 0)
        close(f->direct);
    if (f->fd >= 0)
        close(f->fd);
    free(f->bufs[0]);
    free(f->bufs[1]);
    free(f);
}

static H5FD_t *direct_open(const char *name, unsigned flags, hid_t fapl, haddr_t maxaddr) {
    (void)fapl;
    (void)maxaddr;
    int o = (flags & H5F_ACC_RDWR) ? O_RDWR : O_RDONLY;
    if (flags & H5F_ACC_TRUNC)
        o |= O_TRUNC;
    if (flags & H5F_ACC_CREAT)
        o |= O_CREAT;
    if (flags & H5F_ACC_EXCL)
        o |= O_EXCL;
    direct_t *f = calloc(1, sizeof(direct_t));
    if (f == NULL)
        return NULL;
    f->fd = f->direct = -1;
    pthread_mutex_init(&f->mu, NULL);
    pthread_cond_init(&f->cv, NULL);
    void *a = NULL, *b = NULL;
    int ok = posix_memalign(&a, ALIGN, BUFFER_BYTES) == 0;
    f->bufs[0] = a;
    ok = ok && posix_memalign(&b, ALIGN, BUFFER_BYTES) == 0;
    f->bufs[1] = b;
    f->buf = f->bufs[0];
    f->fd = ok ? open(name, o | O_CLOEXEC, 0666) : -1;
    struct stat st;
    if (f->fd < 0 || fstat(f->fd, &st) < 0) {
        int e = errno;
        free_file(f);
        errno = e;
        return NULL;
    }
#ifdef O_DIRECT
    if (flags & H5F_ACC_RDWR)
        f->direct = open(name, O_WRONLY | O_DIRECT | O_CLOEXEC); /* -1: refused, no matter */
#endif
    f->refused = f->direct < 0;
    /* without a syncer, nothing is synced as the file grows, and the final fsync does all */
    if (!f->refused)
        f->syncer_running = pthread_create(&f->syncer, NULL, syncer, f) == 0;
    if (!f->refused)
        f->thread_running = pthread_create(&f->thread, NULL, block_writer, f) == 0;
    f->eof = (haddr_t)st.st_size;
    f->dev = st.st_dev;
    f->ino = st.st_ino;
    f->start = f->eof;
    return &f->pub;
}

static herr_t direct_close(H5FD_t *file) {
    direct_t *f = (direct_t *)file;
    herr_t r = write_all_gathered(f);
    /* a sync still under way, and its failure */
    if (stop_threads(f) != 0)
        r = -1;
    if (f->fd >= 0 && close(f->fd) < 0)
        r = -1;
    f->fd = -1;
    free_file(f);
    return r;
}

static int direct_cmp(const H5FD_t *a, const H5FD_t *b) {
    const direct_t *x = (const direct_t *)a, *y = (const direct_t *)b;
    if (x->dev != y->dev)
        return x->dev < y->dev ? -1 : 1;
    if (x->ino != y->ino)
        return x->ino < y->ino ? -1 : 1;
    return 0;
}

static herr_t direct_query(const H5FD_t *file, unsigned long *flags) {
    (void)file;
    /* as sec2, but the handle is this driver's own, not a POSIX descriptor; the store asks
     * for the end of allocation (H5Fget_eoa), which HDF5 answers only for drivers that say
     * they can serve SWMR (this one can: every read sees every write before it) */
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA | H5FD_FEAT_SUPPORTS_SWMR_IO;
    return 0;
}

static haddr_t direct_get_eoa(const H5FD_t *file, H5FD_mem_t type) {
    (void)type;
    return ((const direct_t *)file)->eoa;
}

static herr_t direct_set_eoa(H5FD_t *file, H5FD_mem_t type, haddr_t addr) {
    (void)type;
    ((direct_t *)file)->eoa = addr;
    return 0;
}

static haddr_t direct_get_eof(const H5FD_t *file, H5FD_mem_t type) {
    (void)type;
    return ((const direct_t *)file)->eof;
}

static herr_t direct_get_handle(H5FD_t *file, hid_t fapl, void **handle) {
    (void)fapl;
    *handle = file;
    return 0;
}

/* Whether [addr, addr + size) meets the buffer's bytes. */
static int touches(const direct_t *f, haddr_t addr, size_t size) {
    return f->len > 0 && addr < f->start + f->len && f->start < addr + size;
}

static herr_t direct_read(H5FD_t *file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size,
                          void *out) {
    (void)type;
    (void)dxpl;
    direct_t *f = (direct_t *)file;
    /* the block being written may be where this reads: the disk has it first */
    if (wait_idle(f) < 0 || (touches(f, addr, size) && to_os(f) < 0))
        return -1;
    return pread_all(f->fd, out, size, addr) < 0 ? -1 : 0;
}

static herr_t direct_write(H5FD_t *file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size,
                           const void *data) {
    (void)type;
    (void)dxpl;
    direct_t *f = (direct_t *)file;
    if (addr + size > f->eof)
        f->eof = addr + size;
    haddr_t end = f->start + f->len;
    if (size > BLOCK_BYTES || addr < end) {
        /* too large to gather, or below the gathered end (metadata rewritten in place):
         * through the page cache, the block being written and the gathered bytes it meets
         * first */
        if (wait_idle(f) < 0 || (touches(f, addr, size) && write_all_gathered(f) < 0))
            return -1;
        return pwrite_all(f->fd, data, size, addr) < 0 ? -1 : 0;
    }
    if (addr > end || f->len == 0) {
        /* past the gathered end (what lies between is allocated, and written later): what
         * is gathered goes, and gathering starts again here */
        if (write_all_gathered(f) < 0 || begin_at(f, addr) < 0)
            return -1;
    }
    memcpy(f->buf + f->len, data, size);
    f->len += size;
    return f->len >= BLOCK_BYTES ? write_blocks(f) : 0;
}

static herr_t direct_flush(H5FD_t *file, hid_t dxpl, hbool_t closing) {
    (void)dxpl;
    (void)closing;
    direct_t *f = (direct_t *)file;
    return wait_idle(f) < 0 || to_os(f) < 0 ? -1 : 0;
}

static herr_t direct_truncate(H5FD_t *file, hid_t dxpl, hbool_t closing) {
    (void)dxpl;
    (void)closing;
    direct_t *f = (direct_t *)file;
    /* all of it written first: nothing gathered may land past the new end afterwards */
    if (write_all_gathered(f) < 0)
        return -1;
    if (f->eoa != f->eof) {
        if (ftruncate(f->fd, (off_t)f->eoa) < 0)
            return -1;
        f->eof = f->eoa;
    }
    return 0;
}

static herr_t direct_lock(H5FD_t *file, hbool_t rw) {
    int op = (rw ? LOCK_EX : LOCK_SH) | LOCK_NB;
    /* a file system without locks is no reason to refuse the file, as for sec2 */
    if (flock(((direct_t *)file)->fd, op) < 0 && errno != ENOSYS)
        return -1;
    return 0;
}

static herr_t direct_unlock(H5FD_t *file) {
    if (flock(((direct_t *)file)->fd, LOCK_UN) < 0 && errno != ENOSYS)
        return -1;
    return 0;
}

static const H5FD_class_t *direct_class(void) {
    static const H5FD_class_t cls = {
#if H5_VERSION_GE(1, 13, 0)
        .version = H5FD_CLASS_VERSION,
        .value = 4277, /* a driver of this program's own (above H5_VFD_RESERVED) */
#endif
        .name = "batstudy_direct",
        .maxaddr = ((haddr_t)1 << 62) - 1,
        .fc_degree = H5F_CLOSE_WEAK,
        .open = direct_open,
        .close = direct_close,
        .cmp = direct_cmp,
        .query = direct_query,
        .get_eoa = direct_get_eoa,
        .set_eoa = direct_set_eoa,
        .get_eof = direct_get_eof,
        .get_handle = direct_get_handle,
        .read = direct_read,
        .write = direct_write,
        .flush = direct_flush,
        .truncate = direct_truncate,
        .lock = direct_lock,
        .unlock = direct_unlock,
        .fl_map = H5FD_FLMAP_DICHOTOMY,
    };
    return &cls;
}

/* Make `fapl` open files with this driver (registered at the first call; the caller holds
 * the HDF5 lock). Negative on failure. */
herr_t batstudy_direct_set(hid_t fapl) {
    static hid_t id = H5I_INVALID_HID;
    if (id < 0 || H5Iis_valid(id) <= 0)
        id = H5FDregister(direct_class());
    if (id < 0)
        return -1;
    return H5Pset_driver(fapl, id, NULL);
}

/* The file's driver state, or NULL when `file` has another driver. */
static direct_t *of_file(hid_t file) {
    void *handle = NULL;
    if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || handle == NULL)
        return NULL;
    direct_t *f = handle;
    /* HDF5 keeps its own copy of a registered class: known by its name */
    if (f->pub.cls == NULL || f->pub.cls->name == NULL ||
        strcmp(f->pub.cls->name, direct_class()->name) != 0)
        return NULL;
    return f;
}

/* Write everything `file` (opened with this driver) has gathered: its whole blocks to the
 * disk (waiting for them), the rest into the OS. Negative on failure, or when the file has
 * another driver. */
herr_t batstudy_direct_flush(hid_t file) {
    direct_t *f = of_file(file);
    if (f == NULL)
        return -1;
    return write_blocks(f) < 0 || wait_idle(f) < 0 || to_os(f) < 0 ? -1 : 0;
}

/* `*end`: an offset below which every byte `file` (opened with this driver) was given is
 * in the OS, without waiting for anything. Negative on failure (a block that could not be
 * written), or when the file has another driver. */
herr_t batstudy_direct_in_os(hid_t file, uint64_t *end) {
    direct_t *f = of_file(file);
    if (f == NULL)
        return -1;
    pthread_mutex_lock(&f->mu);
    int failed = f->failed;
    *end = f->busy ? f->job_at : f->start + f->in_os;
    pthread_mutex_unlock(&f->mu);
    return failed ? -1 : 0;
}
