// SPDX-License-Identifier: GPL-3.0-or-later
// Counts the collective MPI calls of each rank and the wall time spent in them, for the scaling model of
// analyses/mpi_model.py: the write's fixed cost grows with the number of ranks by the collectives it makes, so they
// are counted here rather than fitted on oversubscribed runs.
//
// A PMPI interposition library: every wrapper below counts its call, times it with PMPI_Wtime and calls PMPI_<name>.
// It is loaded before libmpi, so it also sees the calls HDF5 makes through the dynamic symbol table (its MPI-IO
// calls); the calls Open MPI's components make inside libmpi are not seen.
//   mpicc -shared -fPIC -O2 -o mpi_count.so analyses/mpi_count.c
//   BTOB_MPI_COUNT_DIR=DIR mpirun -n P -x LD_PRELOAD=/abs/mpi_count.so -x BTOB_MPI_COUNT_DIR btob ...
// At MPI_Finalize each rank R writes DIR/rankR.csv: function,class,calls,seconds, one line per function called at
// least once.  class: tree, a collective whose latency grows as log2 P rounds; pair, one whose latency grows as P - 1
// messages (the all-to-all exchanges, and the MPI-IO collectives, whose two-phase exchange between aggregators is
// pairwise).  Nonblocking collectives (Ibcast, Ibarrier) are counted when posted; MPI_Test is not counted.
// No locking: btob calls MPI from its main thread only (MPI_THREAD_FUNNELED).
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#define FUNCTIONS(X)            \
  X(Barrier, tree)              \
  X(Ibarrier, tree)             \
  X(Bcast, tree)                \
  X(Ibcast, tree)               \
  X(Reduce, tree)               \
  X(Allreduce, tree)            \
  X(Exscan, tree)               \
  X(Scan, tree)                 \
  X(Gather, tree)               \
  X(Gatherv, tree)              \
  X(Scatter, tree)              \
  X(Scatterv, tree)             \
  X(Allgather, tree)            \
  X(Allgatherv, tree)           \
  X(Reduce_scatter, tree)       \
  X(Reduce_scatter_block, tree) \
  X(Comm_dup, tree)             \
  X(Alltoall, pair)             \
  X(Alltoallv, pair)            \
  X(Alltoallw, pair)            \
  X(File_open, pair)            \
  X(File_close, pair)           \
  X(File_write_at_all, pair)    \
  X(File_write_all, pair)       \
  X(File_read_at_all, pair)     \
  X(File_read_all, pair)        \
  X(File_set_view, pair)        \
  X(File_set_size, pair)        \
  X(File_set_atomicity, pair)   \
  X(File_sync, pair)            \
  X(File_preallocate, pair)

#define ENUM(name, class) COUNT_##name,
enum { FUNCTIONS(ENUM) COUNT_N };
#define ROW(name, class) {"MPI_" #name, #class},
static const struct {
  const char* function;
  const char* class;
} kind[COUNT_N] = {FUNCTIONS(ROW)};

static struct {
  long calls;
  double seconds;
} tally[COUNT_N];

// The body of every wrapper: time the call to PMPI_<name> with these arguments, count it, return its result.
#define COUNTED(name, ...)                            \
  do {                                                \
    double t0 = PMPI_Wtime();                         \
    int rc = PMPI_##name(__VA_ARGS__);                \
    tally[COUNT_##name].seconds += PMPI_Wtime() - t0; \
    tally[COUNT_##name].calls++;                      \
    return rc;                                        \
  } while (0)

int MPI_Barrier(MPI_Comm comm) { COUNTED(Barrier, comm); }

int MPI_Ibarrier(MPI_Comm comm, MPI_Request* request) { COUNTED(Ibarrier, comm, request); }

int MPI_Bcast(void* buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm) {
  COUNTED(Bcast, buffer, count, datatype, root, comm);
}

int MPI_Ibcast(void* buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm, MPI_Request* request) {
  COUNTED(Ibcast, buffer, count, datatype, root, comm, request);
}

int MPI_Reduce(const void* sendbuf, void* recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
               MPI_Comm comm) {
  COUNTED(Reduce, sendbuf, recvbuf, count, datatype, op, root, comm);
}

int MPI_Allreduce(const void* sendbuf, void* recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  COUNTED(Allreduce, sendbuf, recvbuf, count, datatype, op, comm);
}

int MPI_Exscan(const void* sendbuf, void* recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  COUNTED(Exscan, sendbuf, recvbuf, count, datatype, op, comm);
}

int MPI_Scan(const void* sendbuf, void* recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  COUNTED(Scan, sendbuf, recvbuf, count, datatype, op, comm);
}

int MPI_Gather(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf, int recvcount,
               MPI_Datatype recvtype, int root, MPI_Comm comm) {
  COUNTED(Gather, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
}

int MPI_Gatherv(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf, const int recvcounts[],
                const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm) {
  COUNTED(Gatherv, sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm);
}

int MPI_Scatter(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf, int recvcount,
                MPI_Datatype recvtype, int root, MPI_Comm comm) {
  COUNTED(Scatter, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
}

int MPI_Scatterv(const void* sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype, void* recvbuf,
                 int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm) {
  COUNTED(Scatterv, sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm);
}

int MPI_Allgather(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf, int recvcount,
                  MPI_Datatype recvtype, MPI_Comm comm) {
  COUNTED(Allgather, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
}

int MPI_Allgatherv(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf, const int recvcounts[],
                   const int displs[], MPI_Datatype recvtype, MPI_Comm comm) {
  COUNTED(Allgatherv, sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm);
}

int MPI_Reduce_scatter(const void* sendbuf, void* recvbuf, const int recvcounts[], MPI_Datatype datatype, MPI_Op op,
                       MPI_Comm comm) {
  COUNTED(Reduce_scatter, sendbuf, recvbuf, recvcounts, datatype, op, comm);
}

int MPI_Reduce_scatter_block(const void* sendbuf, void* recvbuf, int recvcount, MPI_Datatype datatype, MPI_Op op,
                             MPI_Comm comm) {
  COUNTED(Reduce_scatter_block, sendbuf, recvbuf, recvcount, datatype, op, comm);
}

// Collective: the ranks agree on the new communicator's context id (a reduction over the ranks).
int MPI_Comm_dup(MPI_Comm comm, MPI_Comm* newcomm) { COUNTED(Comm_dup, comm, newcomm); }

int MPI_Alltoall(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf, int recvcount,
                 MPI_Datatype recvtype, MPI_Comm comm) {
  COUNTED(Alltoall, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
}

int MPI_Alltoallv(const void* sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                  void* recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm) {
  COUNTED(Alltoallv, sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm);
}

int MPI_Alltoallw(const void* sendbuf, const int sendcounts[], const int sdispls[], const MPI_Datatype sendtypes[],
                  void* recvbuf, const int recvcounts[], const int rdispls[], const MPI_Datatype recvtypes[],
                  MPI_Comm comm) {
  COUNTED(Alltoallw, sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm);
}

int MPI_File_open(MPI_Comm comm, const char* filename, int amode, MPI_Info info, MPI_File* fh) {
  COUNTED(File_open, comm, filename, amode, info, fh);
}

int MPI_File_close(MPI_File* fh) { COUNTED(File_close, fh); }

int MPI_File_write_at_all(MPI_File fh, MPI_Offset offset, const void* buf, int count, MPI_Datatype datatype,
                          MPI_Status* status) {
  COUNTED(File_write_at_all, fh, offset, buf, count, datatype, status);
}

int MPI_File_write_all(MPI_File fh, const void* buf, int count, MPI_Datatype datatype, MPI_Status* status) {
  COUNTED(File_write_all, fh, buf, count, datatype, status);
}

int MPI_File_read_at_all(MPI_File fh, MPI_Offset offset, void* buf, int count, MPI_Datatype datatype,
                         MPI_Status* status) {
  COUNTED(File_read_at_all, fh, offset, buf, count, datatype, status);
}

int MPI_File_read_all(MPI_File fh, void* buf, int count, MPI_Datatype datatype, MPI_Status* status) {
  COUNTED(File_read_all, fh, buf, count, datatype, status);
}

int MPI_File_set_view(MPI_File fh, MPI_Offset disp, MPI_Datatype etype, MPI_Datatype filetype, const char* datarep,
                      MPI_Info info) {
  COUNTED(File_set_view, fh, disp, etype, filetype, datarep, info);
}

int MPI_File_set_size(MPI_File fh, MPI_Offset size) { COUNTED(File_set_size, fh, size); }

int MPI_File_set_atomicity(MPI_File fh, int flag) { COUNTED(File_set_atomicity, fh, flag); }

int MPI_File_sync(MPI_File fh) { COUNTED(File_sync, fh); }

int MPI_File_preallocate(MPI_File fh, MPI_Offset size) { COUNTED(File_preallocate, fh, size); }

// Writes the counts after PMPI_Finalize: HDF5 closes what is still open from a callback that MPI_Finalize runs, and
// those calls are counted too.  The rank is taken before, while MPI may still be called.
int MPI_Finalize(void) {
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int rc = PMPI_Finalize();
  const char* dir = getenv("BTOB_MPI_COUNT_DIR");
  if (!dir || !*dir) return rc;
  char path[4096];
  snprintf(path, sizeof path, "%s/rank%d.csv", dir, rank);
  FILE* f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "mpi_count: cannot write %s\n", path);
    return rc;
  }
  fprintf(f, "function,class,calls,seconds\n");
  for (int i = 0; i < COUNT_N; ++i)
    if (tally[i].calls > 0)
      fprintf(f, "%s,%s,%ld,%.9f\n", kind[i].function, kind[i].class, tally[i].calls, tally[i].seconds);
  fclose(f);
  return rc;
}
