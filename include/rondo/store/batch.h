// Several writes of the store as one transaction with one sync: the writes made while a Batch is
// open join it (each stays all or nothing on its own, as a savepoint), and commit() makes them
// durable together. Not committed when destroyed: every write made in it is undone.
//
//   store::Batch batch(db);
//   (void)store::append_event(db, e1);     // not durable yet
//   (void)store::append_event(db, e2);
//   if (Status ok = batch.commit(); !ok) ...  // both on disk, or (kStorage) neither
#pragma once

#include <memory>
#include <optional>

#include "rondo/core/result.h"
#include "rondo/store/store.h"

namespace rondo::store {

class WriteTx;

class Batch {
 public:
  // Opens the transaction (a savepoint inside another batch). A store that cannot begin one
  // (busy past its timeout, gone) leaves the batch failed: the writes go on one by one, as without
  // it, and commit() reports the error.
  explicit Batch(Store& store);
  ~Batch();
  Batch(const Batch&) = delete;
  Batch& operator=(const Batch&) = delete;

  // Errors: kStorage (nothing of the batch is kept then).
  Status commit();

 private:
  Store& store_;
  std::unique_ptr<WriteTx> tx_;
  std::optional<Error> failed_;
};

}  // namespace rondo::store
