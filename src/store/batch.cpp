#include "rondo/store/batch.h"

#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {

Batch::Batch(Store& store) : store_(store) {
  auto begun = guarded(store_, "beginning a batch of writes", [&]() -> Status {
    tx_ = std::make_unique<WriteTx>(connection(store_));
    return Status{};
  });
  if (!begun) failed_ = begun.error();
}

Batch::~Batch() = default;

Status Batch::commit() {
  if (failed_) return *failed_;
  if (!tx_) return Status{};
  return guarded(store_, "committing a batch of writes", [&]() -> Status {
    tx_->commit();
    tx_.reset();
    return Status{};
  });
}

}  // namespace rondo::store
