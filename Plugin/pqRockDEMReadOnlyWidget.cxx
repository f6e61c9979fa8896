#include "pqRockDEMReadOnlyWidget.h"

#include <pqCoreUtilities.h>
#include <vtkCommand.h>
#include <vtkSMDocumentation.h>
#include <vtkSMDoubleVectorProperty.h>
#include <vtkSMIdTypeVectorProperty.h>
#include <vtkSMIntVectorProperty.h>
#include <vtkSMProperty.h>
#include <vtkSMStringVectorProperty.h>

#include <QHBoxLayout>
#include <QLabel>
#include <QRegularExpression>

namespace
{
/// The unit a RockDEM property's documentation names: "Read-only. ... , Pa." -> "Pa".
QString unitOf(vtkSMProperty* property)
{
  vtkSMDocumentation* doc = property->GetDocumentation();
  const QString text = doc && doc->GetDescription() ? QString(doc->GetDescription()) : QString();
  // The quantity is followed by ", <unit>" (the project's documentation convention:
  // "Read-only. Largest axial stress so far, Pa. ...").
  static const QRegularExpression unit(
    R"(,\s*(Pa|s|J|m|m/s|1/s|N/m|N/m\^3|kg|m\^3|m\^2)\s*[.,;(])");
  const QRegularExpressionMatch match = unit.match(text);
  return match.hasMatch() ? match.captured(1) : QString();
}
}

pqRockDEMReadOnlyWidget::pqRockDEMReadOnlyWidget(
  vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent)
  : Superclass(proxy, parent)
  , Label(new QLabel(this))
{
  this->setProperty(property);
  this->Label->setObjectName("Value");
  this->Label->setWordWrap(true);
  this->Label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  this->Label->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Preferred);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(this->Label);
  pqCoreUtilities::connect(property, vtkCommand::ModifiedEvent, this, SLOT(updateText()));
  this->updateText();
}

pqRockDEMReadOnlyWidget::~pqRockDEMReadOnlyWidget() = default;

QString pqRockDEMReadOnlyWidget::text(vtkSMProperty* property)
{
  QStringList values;
  if (auto* ids = vtkSMIdTypeVectorProperty::SafeDownCast(property))
  {
    for (unsigned int k = 0; k < ids->GetNumberOfElements(); ++k)
    {
      values << QString::number(static_cast<qlonglong>(ids->GetElement(k)));
    }
  }
  else if (auto* ints = vtkSMIntVectorProperty::SafeDownCast(property))
  {
    for (unsigned int k = 0; k < ints->GetNumberOfElements(); ++k)
    {
      values << QString::number(ints->GetElement(k));
    }
  }
  else if (auto* doubles = vtkSMDoubleVectorProperty::SafeDownCast(property))
  {
    for (unsigned int k = 0; k < doubles->GetNumberOfElements(); ++k)
    {
      values << QString::number(doubles->GetElement(k), 'g', 6);
    }
  }
  else if (auto* strings = vtkSMStringVectorProperty::SafeDownCast(property))
  {
    for (unsigned int k = 0; k < strings->GetNumberOfElements(); ++k)
    {
      values << QString(strings->GetElement(k) ? strings->GetElement(k) : "");
    }
    return values.join("\n");
  }
  const QString unit = unitOf(property);
  return values.join("  ") + (unit.isEmpty() || values.isEmpty() ? QString() : " " + unit);
}

void pqRockDEMReadOnlyWidget::updateText()
{
  const QString shown = text(this->property());
  this->Label->setText(shown.isEmpty() ? QString("-") : shown);
  this->Label->setToolTip(shown);
}
