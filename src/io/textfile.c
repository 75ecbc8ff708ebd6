/* Text files written like the images: a temporary file in the target's folder, renamed into
 * place (or handed to a batch), so a failed write leaves no partial file (refray export). */
#include <errno.h>
#include <stdio.h>

#include "io_internal.h"
#include "refray/image.h"

RfStatus rf_write_text(const char *path, const char *text, size_t len, RfWriteBatch *batch, char *err,
                       size_t err_size)
{
    RfAtomicFile f;
    RfStatus st = rf_atomic_open(&f, path, err, err_size);
    if (st != RF_OK)
        return st;
    st = rf_atomic_stdio(&f, err, err_size);
    if (st != RF_OK) {
        rf_atomic_abort(&f);
        return st;
    }
    if (len && fwrite(text, 1, len, f.fp) != len) {
        int e = errno;
        rf_atomic_abort(&f);
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot write", e ? e : EIO);
    }
    return rf_atomic_finish(&f, batch, err, err_size);
}
