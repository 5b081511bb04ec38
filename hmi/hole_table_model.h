// The process database as a Qt table model (one row per hole, the columns
// of docs/design.md §6 fields 1–18 and the focus offset): what the process-database
// screen's table shows and edits. Every edit goes through
// ProcessDatabase::put, so it is validated and stored in one transaction; a
// refused edit changes nothing and `refused` says why (hole, field, range).
#pragma once

#include <QAbstractTableModel>
#include <QString>

#include <vector>

#include "hmi/process_db.h"

namespace lcnc::hmi {

class HoleTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  enum Column : int {
    kHole,
    kX,
    kY,
    kZ,
    kA,
    kC,
    kFeed,
    kLayerFeed,
    kLayers,
    kDepth,
    kPower,
    kStartRadius,
    kEndRadius,
    kTurns,
    kScanSpeed,
    kWedgeSpeed,
    kBeamOffset,
    kProcess,
    kFocus,
    kColumnCount
  };

  explicit HoleTableModel(ProcessDatabase& db, QObject* parent = nullptr);

  // Reads the table anew (after an import, or another writer).
  void reload();
  [[nodiscard]] const HoleRecord& record(int row) const { return rows_.at(static_cast<std::size_t>(row)); }

  [[nodiscard]] int rowCount(const QModelIndex& parent = {}) const override;
  [[nodiscard]] int columnCount(const QModelIndex& parent = {}) const override;
  [[nodiscard]] QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
  [[nodiscard]] QVariant headerData(int section, Qt::Orientation orientation,
                                    int role = Qt::DisplayRole) const override;
  [[nodiscard]] Qt::ItemFlags flags(const QModelIndex& index) const override;
  bool setData(const QModelIndex& index, const QVariant& value, int role = Qt::EditRole) override;

 signals:
  void refused(const QString& message);

 private:
  ProcessDatabase& db_;
  std::vector<HoleRecord> rows_;
};

}  // namespace lcnc::hmi
