// The HMI's languages (Qt Linguist): English in the sources, Chinese (zh_CN)
// and Russian (ru) in hmi/translations/*.ts, compiled to .qm at build time.
#pragma once

#include <QString>
#include <QStringList>

class QCoreApplication;

namespace lcnc::hmi {

// The languages there are translations for, besides English ("en").
[[nodiscard]] QStringList available_languages();

// Installs the translation of `language` ("zh_CN", "ru"; "en" or "" for
// none; "system" for the system locale's, English when there is none).
// False, with `why`, when a language asked for by name has no translation.
bool install_language(const QString& language, QString* why = nullptr);

}  // namespace lcnc::hmi
