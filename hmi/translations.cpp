#include "hmi/translations.h"

#include <QCoreApplication>
#include <QDir>
#include <QLocale>
#include <QTranslator>

#include "common/share_path.h"

namespace lcnc::hmi {
namespace {

// $LASERCNC_QM_DIR, else an installed tree's share/lasercnc/i18n, else the
// build's.
QString qm_dir() {
  const QByteArray env = qgetenv("LASERCNC_QM_DIR");
  if (!env.isEmpty()) return QString::fromLocal8Bit(env);
  const QString shared = QString::fromStdString(share_path("i18n"));
  return QDir(shared).exists() ? shared : QStringLiteral(LCNC_HMI_QM_DIR);
}

QTranslator* installed = nullptr;

}  // namespace

QStringList available_languages() { return {"zh_CN", "ru"}; }

bool install_language(const QString& language, QString* why) {
  if (installed != nullptr) {
    QCoreApplication::removeTranslator(installed);
    delete installed;
    installed = nullptr;
  }
  QString lang = language;
  if (lang == "system") {
    lang = QLocale::system().name();  // "ru_RU", "zh_CN", "en_US"
    if (!available_languages().contains(lang)) lang = lang.section('_', 0, 0);
    if (!available_languages().contains(lang)) return true;  // English
  }
  if (lang.isEmpty() || lang == "en") return true;
  auto* t = new QTranslator();
  if (!available_languages().contains(lang) || !t->load("lasercnc_hmi_" + lang, qm_dir())) {
    delete t;
    if (why != nullptr)
      *why =
          QString("no translation for '%1' (there are: en, %2)").arg(lang, available_languages().join(", "));
    return false;
  }
  QCoreApplication::installTranslator(t);
  installed = t;
  return true;
}

}  // namespace lcnc::hmi
